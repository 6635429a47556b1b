// The PVS-culled frame equals the unculled frame pixel for pixel, on a four-cell bundle with a three-node
// tree whose PVS is conservative (each room leaves out only the other room's back-facing shared wall).
#include <gtest/gtest.h>

#include <cmath>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace pvs_equivalence_test {  // named, not anonymous: the suite compiles as unity batches

class PvsEquivalenceTest : public ::testing::TestWithParam<BackendKind> {};

// The two rooms as four cells, each polygon diced 3x3: several ranges per polygon list, so merging and
// ordering are exercised.
std::unique_ptr<model::Bundle> open_four_cells(const std::string& name) {
  TwoRooms scene;
  scene.four_cells = true;
  scene.subdivisions = 3;
  return open_two_rooms(scene, name);
}

TEST_P(PvsEquivalenceTest, CulledFrameEqualsUnculledFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("pvs_equivalence");
  ASSERT_EQ(bundle->cells().size(), 4u);
  Renderer culled(*bundle), unculled(*bundle);
  unculled.set_pvs_culling(false);
  for (Renderer* r : {&culled, &unculled}) r->set_frustum_culling(false);  // the PVS alone
  int views = 0;
  bool cells_seen[4] = {};
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (double y : {1.0, 3.0})
      for (int turn = 0; turn < 8; ++turn) {
        View view;
        view.eye = {x, y, 1.6};
        const double a = turn * 0.785398163;
        view.forward = {std::cos(a), std::sin(a), -0.1};
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
  int fewer = 0;
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (int turn = 0; turn < 8; ++turn) {
      View view;
      view.eye = {x, 1.5, 1.6};
      const double a = turn * 0.785398163;
      view.forward = {std::cos(a), std::sin(a), 0.2 * std::sin(3 * a)};
      culled.draw(view, kWidth, kHeight);
      unculled.draw(view, kWidth, kHeight);
      ASSERT_EQ(culled.read_pixels(kWidth, kHeight).rgba, unculled.read_pixels(kWidth, kHeight).rgba)
          << "eye " << x << " turn " << turn;
      fewer += culled.last_stats().polygons_drawn + 3 < unculled.last_stats().polygons_drawn;
    }
  EXPECT_GT(fewer, 16) << "the frustum should drop polygons behind the viewer in most views";
}

// Drawing the opaque clusters nearest first changes the order of the draw, never a pixel: at full detail
// and at the flat coarse level, from every cell.
TEST_P(PvsEquivalenceTest, NearestFirstFrameEqualsCompilerOrderFrame) {
  auto backend = headless(GetParam());
  auto bundle = open_four_cells("nearest_first_equivalence");
  Renderer nearest(*bundle), in_order(*bundle);
  in_order.set_nearest_first(false);
  int reordered = 0, views = 0;
  for (double x : {1.0, 3.0, 5.0, 7.0})
    for (int turn = 0; turn < 8; ++turn)
      for (const float patch_weight : {1.0f, 0.0f}) {
        View view;
        view.eye = {x, 1.5, 1.6};
        const double a = turn * 0.785398163;
        view.forward = {std::cos(a), std::sin(a), -0.2};
        const DrawOptions options{.patch_weight = patch_weight};
        nearest.draw(view, kWidth, kHeight, options);
        in_order.draw(view, kWidth, kHeight, options);
        ASSERT_EQ(nearest.read_pixels(kWidth, kHeight).rgba, in_order.read_pixels(kWidth, kHeight).rgba)
            << "eye " << x << " turn " << turn << " patch weight " << patch_weight;
        EXPECT_EQ(nearest.last_stats().triangles_drawn, in_order.last_stats().triangles_drawn);
        reordered += nearest.last_stats().draw_ranges > in_order.last_stats().draw_ranges;
        ++views;
      }
  EXPECT_EQ(views, 64);
  EXPECT_GT(reordered, 8) << "nearest first should split the compiler's merged ranges in many views";
}

INSTANTIATE_TEST_SUITE_P(Headless, PvsEquivalenceTest,
                         ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace pvs_equivalence_test
}  // namespace walk::render::test
