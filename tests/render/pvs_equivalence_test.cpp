// The PVS-culled frame equals the unculled frame pixel for pixel, on a four-cell bundle with a three-node
// tree whose PVS is conservative (each room leaves out only the other room's back-facing shared wall).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace pvs_equivalence_test {  // named, not anonymous: the suite compiles as unity batches

class PvsEquivalenceTest : public ::testing::TestWithParam<BackendKind> {};

// The two rooms as four cells, each polygon diced 3x3: several ranges per polygon list, so merging and
// ordering are exercised.
std::unique_ptr<model::Bundle> open_four_cells(const std::string& name, bool crate = false) {
  TwoRooms scene;
  scene.four_cells = true;
  scene.crate = crate;
  scene.subdivisions = 3;
  return open_two_rooms(scene, name);
}

constexpr double kEighthTurn = 0.785398163;  // radians

// A view from (x, y) at eye height, turned `heading` radians from +x and tilted by `down` (forward's z).
View view_from(double x, double y, double heading, double down) {
  View view;
  view.eye = {x, y, 1.6};
  view.forward = {std::cos(heading), std::sin(heading), down};
  return view;
}

TEST_P(PvsEquivalenceTest, CulledFrameEqualsUnculledFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("pvs_equivalence");
  ASSERT_EQ(bundle->cells().size(), 4u);
  Renderer culled(*bundle), unculled(*bundle);
  unculled.set_pvs_culling(false);
  for (Renderer* r : {&culled, &unculled}) {
    r->set_frustum_culling(false);  // the PVS alone
    r->set_occlusion_culling(false);
  }
  int views = 0;
  bool cells_seen[4] = {};
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (double y : {1.0, 3.0})
      for (int turn = 0; turn < 8; ++turn) {
        const View view = view_from(x, y, turn * kEighthTurn, -0.1);
        culled.draw(view, kWidth, kHeight);
        unculled.draw(view, kWidth, kHeight);
        const Image a_image = culled.read_pixels(kWidth, kHeight);
        const Image b_image = unculled.read_pixels(kWidth, kHeight);
        const auto& stats = culled.last_stats();
        ASSERT_LT(stats.cell, 4u);
        cells_seen[stats.cell] = true;
        EXPECT_EQ(stats.polygons_drawn + 3, unculled.last_stats().polygons_drawn) << "cell " << stats.cell;
        ASSERT_EQ(a_image.rgba, b_image.rgba) << "eye " << x << "," << y << " turn " << turn;
        ++views;
      }
  EXPECT_EQ(views, 64);
  for (bool seen : cells_seen) EXPECT_TRUE(seen);
}

// Frustum culling of clusters on top of the PVS drops polygons behind or beside the viewer, never a visible
// one.
TEST_P(PvsEquivalenceTest, FrustumCulledFrameEqualsUnculledFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("frustum_equivalence");
  Renderer culled(*bundle), unculled(*bundle);
  culled.set_frustum_culling(true);  // the default
  unculled.set_pvs_culling(false);
  unculled.set_frustum_culling(false);
  for (Renderer* r : {&culled, &unculled}) r->set_occlusion_culling(false);  // the frustum alone
  int fewer = 0;
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (int turn = 0; turn < 8; ++turn) {
      const double a = turn * kEighthTurn;
      const View view = view_from(x, 1.5, a, 0.2 * std::sin(3 * a));
      culled.draw(view, kWidth, kHeight);
      unculled.draw(view, kWidth, kHeight);
      ASSERT_EQ(culled.read_pixels(kWidth, kHeight).rgba, unculled.read_pixels(kWidth, kHeight).rgba)
          << "eye " << x << " turn " << turn;
      fewer += culled.last_stats().polygons_drawn + 3 < unculled.last_stats().polygons_drawn;
    }
  EXPECT_GT(fewer, 16) << "the frustum should drop polygons behind the viewer in most views";
}

// Drawing the opaque clusters nearest first changes the order of the draw, never a pixel: at full detail
// and at the flat coarse level, from every cell; each cluster on its own (the most reordering: these
// rooms' clusters are smaller than a run) and in runs as the kiosk draws them.
TEST_P(PvsEquivalenceTest, NearestFirstFrameEqualsCompilerOrderFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("nearest_first_equivalence");
  Renderer nearest(*bundle), in_runs(*bundle), in_order(*bundle);
  nearest.set_nearest_first(true, 0);
  in_order.set_nearest_first(false);
  for (Renderer* r : {&nearest, &in_runs, &in_order}) r->set_occlusion_culling(false);  // the order alone
  int reordered = 0, views = 0;
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (int turn = 0; turn < 8; ++turn)
      for (const float patch_weight : {1.0f, 0.0f}) {
        const View view = view_from(x, 1.5, turn * kEighthTurn, -0.2);
        const DrawOptions options{.patch_weight = patch_weight};
        nearest.draw(view, kWidth, kHeight, options);
        in_runs.draw(view, kWidth, kHeight, options);
        in_order.draw(view, kWidth, kHeight, options);
        const auto expected = in_order.read_pixels(kWidth, kHeight).rgba;
        ASSERT_EQ(nearest.read_pixels(kWidth, kHeight).rgba, expected)
            << "eye " << x << " turn " << turn << " patch weight " << patch_weight;
        ASSERT_EQ(in_runs.read_pixels(kWidth, kHeight).rgba, expected)
            << "in runs: eye " << x << " turn " << turn << " patch weight " << patch_weight;
        EXPECT_EQ(nearest.last_stats().triangles_drawn, in_order.last_stats().triangles_drawn);
        reordered += nearest.last_stats().draw_ranges > in_order.last_stats().draw_ranges;
        ++views;
      }
  EXPECT_EQ(views, 64);
  EXPECT_GT(reordered, 8) << "nearest first should split the compiler's merged ranges in many views";
}

// The coarse form's vertices shared between polygons (each triangle's flat light from a vertex of its own
// polygon) draw what each polygon's own vertices draw, pixel for pixel: at the coarse level, at full and
// half resolution, from every cell, with the dimmers away from their defaults.
TEST_P(PvsEquivalenceTest, SharedCoarseVerticesDrawTheSameFrame) {
  auto backend = headless(GetParam());
  TwoRooms scene;
  scene.four_cells = true;
  scene.crate = true;
  scene.subdivisions = 3;
  scene.coarse_form = true;
  // One cluster of every polygon, which every cell sees: vertices are shared within a cluster, so the
  // walls' corners, where polygons of different light meet, share theirs.
  model::BundleContents contents = make_two_rooms(scene);
  model::ClusterRecord all{};
  for (int a = 0; a < 3; ++a) {
    all.bounds_min[a] = -100.0f;
    all.bounds_max[a] = 100.0f;
  }
  all.polygon_count = std::uint32_t(contents.polygons.size());
  contents.clusters = {all};
  contents.cluster_polygons.resize(contents.polygons.size());
  std::iota(contents.cluster_polygons.begin(), contents.cluster_polygons.end(), 0u);
  contents.pvs = {0};
  for (auto& cell : contents.cells) cell.pvs_first = 0, cell.pvs_count = 1;
  auto bundle = open_bundle(std::move(contents), "shared_coarse_vertices");
  ASSERT_FALSE(bundle->coarse_indices().empty());
  Renderer shared(*bundle), own(*bundle);
  own.set_shared_coarse_vertices(false);
  std::vector<float> levels(bundle->circuits().size());
  for (std::size_t c = 0; c < levels.size(); ++c) levels[c] = 0.3f + 0.5f * float(c % 2);
  int views = 0, lit = 0;
  for (Renderer* r : {&shared, &own}) r->set_dimmers(levels);
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (int turn = 0; turn < 8; ++turn)
      for (const float resolution : {1.0f, 0.5f}) {
        const View view = view_from(x, 1.5, turn * kEighthTurn, -0.2);
        const DrawOptions options{.patch_weight = 0.0f, .resolution = resolution};
        shared.draw(view, kWidth, kHeight, options);
        own.draw(view, kWidth, kHeight, options);
        const auto expected = own.read_pixels(kWidth, kHeight).rgba;
        ASSERT_EQ(shared.read_pixels(kWidth, kHeight).rgba, expected)
            << "eye " << x << " turn " << turn << " resolution " << resolution;
        lit += std::any_of(expected.begin(), expected.end(), [](std::uint8_t c) { return c > 8; });
        ++views;
      }
  EXPECT_EQ(views, 64);
  EXPECT_EQ(lit, 64) << "every view shows lit walls";
}

// Occlusion culling leaves out clusters behind the walls nearest the eye, never a pixel: at full detail and
// at the flat coarse level, from every cell, with and without a jittered sub-pixel offset; and it must hide
// something (the crate behind the shared wall, seen from room A; B's walls all meet that wall, and a box
// touching an occluder is never hidden). Without the portal walk, which would leave the crate out where
// the doorway's rectangle misses it, so the occlusion buffer has that to do.
TEST_P(PvsEquivalenceTest, OcclusionCulledFrameEqualsUnculledFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("occlusion_equivalence", true);
  Renderer occluded(*bundle), unoccluded(*bundle);
  unoccluded.set_occlusion_culling(false);
  for (Renderer* r : {&occluded, &unoccluded}) r->set_portal_culling(false);
  occluded.set_adaptive_occlusion_culling(false);  // cull every view, however little it hides
  int hiding = 0, views = 0;
  // From room A, looking towards the shared wall, and from room B, where nothing hides the crate.
  for (double x : {0.5, 1.5, 2.5, 3.5, 6.0})
    for (double y : {0.5, 1.0, 3.0, 3.5})
      for (int turn = -2; turn <= 2; ++turn)
        for (const float patch_weight : {1.0f, 0.0f}) {
          const View view = view_from(x, y, turn * 0.5, -0.2);
          const DrawOptions options{.patch_weight = patch_weight, .jitter_x = 0.37f * float(turn & 1)};
          occluded.draw(view, kWidth, kHeight, options);
          unoccluded.draw(view, kWidth, kHeight, options);
          ASSERT_EQ(occluded.read_pixels(kWidth, kHeight).rgba, unoccluded.read_pixels(kWidth, kHeight).rgba)
              << "eye " << x << "," << y << " turn " << turn << " patch weight " << patch_weight;
          const auto& with = occluded.last_stats();
          EXPECT_EQ(with.triangles_drawn + with.triangles_occluded, unoccluded.last_stats().triangles_drawn);
          EXPECT_EQ(unoccluded.last_stats().triangles_occluded, 0u);
          hiding += with.triangles_occluded > 0;
          ++views;
        }
  EXPECT_EQ(views, 200);
  EXPECT_GT(hiding, 20) << "the walls near the eye should hide clusters in many views";
}

INSTANTIATE_TEST_SUITE_P(Headless, PvsEquivalenceTest,
                         ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace pvs_equivalence_test
}  // namespace walk::render::test
