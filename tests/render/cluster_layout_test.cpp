// Clusters to index ranges: the layout copies each cluster's polygons together (opaque, then glass), skips
// what is not drawn, keeps the compiler's order, and a frame's list merges clusters that meet and drops
// those outside the frustum.
#include "render/cluster_layout.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <set>
#include <vector>

#include "model/model.hpp"

namespace walk::render {
namespace cluster_layout_test {  // named, not anonymous: the suite compiles as unity batches

using R = model::Role;

// Polygon p is a square of two triangles at x = p (4 vertices, 6 indices), its indices in id order.
struct Scene {
  std::vector<model::PolygonRecord> polygons;
  std::vector<model::VertexRecord> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<model::ClusterRecord> clusters;
  std::vector<std::uint32_t> cluster_polygons;
  explicit Scene(std::initializer_list<R> roles) {
    for (R role : roles) {
      model::PolygonRecord p{};
      p.first_index = std::uint32_t(indices.size());
      p.index_count = 6;
      p.first_vertex = std::uint32_t(vertices.size());
      p.vertex_count = 4;
      p.role = std::uint32_t(role);
      const float x = float(polygons.size());
      for (const auto& [y, z] : {std::pair{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}}) {
        model::VertexRecord v{};
        v.position[0] = x, v.position[1] = y, v.position[2] = z;
        vertices.push_back(v);
      }
      for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(p.first_vertex + k);
      polygons.push_back(p);
    }
  }
  void cluster(std::initializer_list<std::uint32_t> ids) {
    model::ClusterRecord c{};
    c.polygon_first = std::uint32_t(cluster_polygons.size());
    c.polygon_count = std::uint32_t(ids.size());
    cluster_polygons.insert(cluster_polygons.end(), ids);
    clusters.push_back(c);
  }
  [[nodiscard]] LayoutInput input() const {
    return {polygons, vertices, indices, {}, {}, clusters, cluster_polygons, {}, {}};
  }
};

TEST(ClusterLayout, ClustersAreRangesInTheCompilersOrderWithGlassApartAndHolesSkipped) {
  Scene s(
      {R::Opaque, R::Opaque, R::Glass, R::Opening, R::Luminaire, R::Ignored, R::Opaque, R::Glass, R::Glass});
  s.cluster({6, 4});     // cluster 0: first drawn index 24, so laid out after cluster 1
  s.cluster({1, 0, 2});  // cluster 1: first index 0; glass 2 goes to the glass region
  s.cluster({3});        // cluster 2: an opening only, nothing drawn
  // 7 and 8 (glass) and 5 (ignored) are in no cluster: 7 and 8 become units of their own, 5 is not drawn.
  const ClusterLayout layout = lay_out_clusters(s.input());
  ASSERT_EQ(layout.units(), 5u);
  EXPECT_EQ(layout.unit_of[1], 0u);
  EXPECT_EQ(layout.unit_of[0], 1u);
  EXPECT_EQ(layout.unit_of[2], 4u) << "nothing drawn: last";
  EXPECT_EQ(layout.drawn[0], 3u);
  EXPECT_EQ(layout.drawn[4], 0u);
  // Opaque 0, 1, 4, 6 then glass 2, 7, 8: 7 polygons of 6 indices, the opening and the ignored face dropped.
  ASSERT_EQ(layout.fine.indices.size(), 42u);
  EXPECT_EQ(layout.fine.opaque[0].first, 0u);
  EXPECT_EQ(layout.fine.opaque[0].count, 12u);
  EXPECT_EQ(layout.fine.opaque[1].first, 12u);
  EXPECT_EQ(layout.fine.glass[0].first, 24u);
  EXPECT_EQ(layout.fine.glass[0].count, 6u);
  // Each polygon's new range holds its own indices.
  for (std::uint32_t p : {0u, 1u, 2u, 4u, 6u, 7u, 8u}) {
    const auto& moved = layout.fine.polygons[p];
    ASSERT_EQ(moved.index_count, 6u) << p;
    for (std::uint32_t k = 0; k < 6; ++k)
      EXPECT_EQ(layout.fine.indices[moved.first_index + k], s.indices[s.polygons[p].first_index + k]) << p;
  }
  EXPECT_EQ(layout.fine.polygons[3].index_count, 0u) << "the opening is not drawn";
  EXPECT_EQ(layout.fine.polygons[5].index_count, 0u) << "the ignored face is not drawn";
  // The box of cluster 0 (polygons 4 and 6) spans x 4..6.
  EXPECT_EQ(layout.boxes[1].lo[0], 4.0f);
  EXPECT_EQ(layout.boxes[1].hi[0], 6.0f);

  const DrawList all = cluster_draw_list(layout, layout.fine, all_units(layout), nullptr);
  EXPECT_EQ(all.polygons, 7u);
  EXPECT_EQ(all.triangles, 14u);
  ASSERT_EQ(all.opaque.counts.size(), 1u) << "every opaque cluster meets the next";
  EXPECT_EQ(all.opaque.counts[0], 24);
  ASSERT_EQ(all.glass.counts.size(), 1u);
  EXPECT_EQ(all.glass.byte_offsets[0], 24u * sizeof(std::uint32_t));

  // A PVS of clusters 0 and 2 (ids out of range and repeats dropped): one opaque range, no glass.
  const std::vector<std::uint32_t> pvs{2, 0, 0, 99};
  const auto units = units_of(layout, pvs);
  ASSERT_EQ(units.size(), 2u);
  const DrawList some = cluster_draw_list(layout, layout.fine, units, nullptr);
  EXPECT_EQ(some.polygons, 2u);
  ASSERT_EQ(some.opaque.counts.size(), 1u);
  EXPECT_EQ(some.opaque.byte_offsets[0], 12u * sizeof(std::uint32_t));
  EXPECT_TRUE(some.glass.empty());
}

TEST(ClusterLayout, WithoutClustersEachPolygonIsAUnitAndPvsIdsArePolygons) {
  Scene s({R::Opaque, R::Glass, R::Opaque});
  const ClusterLayout layout = lay_out_clusters(s.input());
  ASSERT_EQ(layout.units(), 3u);
  const std::vector<std::uint32_t> pvs{0, 2};
  const DrawList list = cluster_draw_list(layout, layout.fine, units_of(layout, pvs), nullptr);
  EXPECT_EQ(list.polygons, 2u);
  ASSERT_EQ(list.opaque.counts.size(), 1u) << "0 and 2 meet once the glass between them is laid out apart";
  EXPECT_EQ(list.opaque.counts[0], 12);
}

TEST(ClusterLayout, TheFrustumDropsClustersWhollyBehindTheEyeAndKeepsThoseAcrossIt) {
  Scene s({R::Opaque, R::Opaque, R::Opaque, R::Opaque});
  s.cluster({0});
  s.cluster({1, 2});
  s.cluster({3});
  const ClusterLayout layout = lay_out_clusters(s.input());
  // Eye at x = 1.5 looking along +x: the square at x = 0 and 1 are behind it (cluster 0 wholly, cluster 1
  // spans the eye's plane), x = 3 ahead.
  const glm::mat4 vp =
      glm::perspective(glm::radians(60.0f), 1.0f, 0.05f, 100.0f) *
      glm::lookAt(glm::vec3(1.5f, 0.5f, 0.5f), glm::vec3(2.5f, 0.5f, 0.5f), glm::vec3(0, 0, 1));
  const Frustum frustum(vp);
  const DrawList list = cluster_draw_list(layout, layout.fine, all_units(layout), &frustum);
  EXPECT_EQ(list.polygons, 3u);
  ASSERT_EQ(list.opaque.counts.size(), 1u);
  EXPECT_EQ(list.opaque.byte_offsets[0], 6u * sizeof(std::uint32_t));
  EXPECT_FALSE(frustum.touches(empty_box())) << "an empty box is never drawn";
  EXPECT_TRUE(frustum.touches(Box{{1.4f, 0.4f, 0.4f}, {1.6f, 0.6f, 0.6f}})) << "a box around the eye is";
}

// Nearest first, each unit on its own (runs of 0 triangles): opaque ranges by their boxes' distance from the
// eye (0 for a box around it), equal distances by unit, units still adjacent merged; glass in the units'
// order whatever the eye.
TEST(ClusterLayout, NearestFirstOrdersOpaqueRangesByBoxDistanceAndKeepsGlassInOrder) {
  Scene s({R::Opaque, R::Opaque, R::Opaque, R::Opaque, R::Opaque, R::Glass, R::Glass});
  for (std::uint32_t p = 0; p < 5; ++p) s.cluster({p});
  s.cluster({5});
  s.cluster({6});
  const ClusterLayout layout = lay_out_clusters(s.input());
  const auto offsets_in_units = [](const DrawBatch& batch) {
    std::vector<std::uint32_t> units;
    for (std::size_t i = 0; i < batch.counts.size(); ++i)
      for (std::int32_t k = 0; k < batch.counts[i]; k += 6)
        units.push_back(std::uint32_t(batch.byte_offsets[i] / sizeof(std::uint32_t) + std::uint32_t(k)) / 6);
    return units;
  };
  // Squares sit at x = 0 .. 6 (glass at 5 and 6). An eye at x = 3.5: squares 3 and 4 are 0.5 m away (a tie,
  // unit order), 2 at 1.5, 1 at 2.5, 0 at 3.5.
  const glm::vec3 eye(3.5f, 0.5f, 0.5f);
  const DrawList near =
      cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, nullptr, nullptr, &eye, 0);
  EXPECT_EQ(offsets_in_units(near.opaque), (std::vector<std::uint32_t>{3, 4, 2, 1, 0}));
  EXPECT_EQ(near.opaque.counts.size(), 4u) << "3 and 4 stay adjacent and merge";
  ASSERT_EQ(near.glass.counts.size(), 1u);
  EXPECT_EQ(near.glass.byte_offsets[0], 30u * sizeof(std::uint32_t)) << "glass in order, merged";
  EXPECT_EQ(near.glass.counts[0], 12);
  // An eye inside square 1's box (distance 0) draws it first; the same units and triangles as without an eye.
  const glm::vec3 inside(1.0f, 0.5f, 0.5f);
  const DrawList from_one =
      cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, nullptr, nullptr, &inside, 0);
  EXPECT_EQ(offsets_in_units(from_one.opaque), (std::vector<std::uint32_t>{1, 0, 2, 3, 4}));
  const DrawList in_order = cluster_draw_list(layout, layout.fine, all_units(layout), nullptr);
  EXPECT_EQ(offsets_in_units(in_order.opaque), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(in_order.opaque.counts.size(), 1u);
  EXPECT_EQ(from_one.triangles, in_order.triangles);
  EXPECT_EQ(from_one.polygons, in_order.polygons);
}

// Nearest first in runs: units adjacent in the buffer go together up to the run's triangles, placed by
// their nearest unit (ties by their first unit); a unit larger than a run is its own.
TEST(ClusterLayout, NearestFirstSortsRunsOfAdjacentUnitsUpToTheirTriangles) {
  Scene s({R::Opaque, R::Opaque, R::Opaque, R::Opaque, R::Opaque});
  for (std::uint32_t p = 0; p < 5; ++p) s.cluster({p});
  const ClusterLayout layout = lay_out_clusters(s.input());
  const auto firsts = [](const DrawBatch& batch) {
    std::vector<std::uint32_t> units;
    for (const std::uintptr_t offset : batch.byte_offsets) units.push_back(std::uint32_t(offset / 4 / 6));
    return units;
  };
  // Squares (2 triangles each) at x = 0 .. 5; the eye at x = 3.5. Runs of 4 triangles: {0, 1} (nearest 2.5),
  // {2, 3} (0.5), {4} (0.5, after {2, 3} by its first unit). {2, 3} and {4} meet again in the buffer.
  const glm::vec3 eye(3.5f, 0.5f, 0.5f);
  const DrawList runs =
      cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, nullptr, nullptr, &eye, 4);
  EXPECT_EQ(firsts(runs.opaque), (std::vector<std::uint32_t>{2, 0}));
  EXPECT_EQ(runs.opaque.counts, (std::vector<std::int32_t>{18, 12}));
  // Runs of 1 triangle: smaller than a unit, so each unit is its own run.
  const DrawList single =
      cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, nullptr, nullptr, &eye, 1);
  EXPECT_EQ(firsts(single.opaque), (std::vector<std::uint32_t>{3, 2, 1, 0}));
  // The default run holds all five: the compiler's order, one range.
  const DrawList whole =
      cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, nullptr, nullptr, &eye);
  EXPECT_EQ(firsts(whole.opaque), (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(whole.opaque.counts, (std::vector<std::int32_t>{30}));
  EXPECT_EQ(whole.triangles, runs.triangles);
}

// A cluster whose whole box (a unit square: diagonal sqrt 2 m) spans at most the pixel budget is left out,
// at the budget's edge included; never at full detail, nor with the eye in its box. 100 pixels a radian:
// the square spans 1 pixel at 141.42 m.
TEST(ClusterLayout, ClustersSmallerThanThePixelBudgetAreLeftOut) {
  Scene s({R::Opaque, R::Opaque});
  s.cluster({0});
  s.cluster({1});
  const ClusterLayout layout = lay_out_clusters(s.input());
  LodChoice lod{glm::vec3(-141.0f, 0.5f, 0.5f), 100.0f, 1.0f};
  EXPECT_FALSE(too_small_to_draw(layout, 0, lod)) << "141 m: 1.003 pixels";
  lod.eye.x = -142.0f;
  EXPECT_TRUE(too_small_to_draw(layout, 0, lod)) << "142 m: 0.996 pixels";
  lod.max_pixels = 0.0f;
  EXPECT_FALSE(too_small_to_draw(layout, 0, lod)) << "full detail draws everything";
  lod = {glm::vec3(0.0f, 0.5f, 0.5f), 1e-6f, 1e9f};
  EXPECT_FALSE(too_small_to_draw(layout, 0, lod)) << "the eye in its box: distance 0";
  // Square 0 at 141.9 m spans 0.99660 pixels, square 1 at 142.9 m 0.98963: a budget of 0.9931 between.
  lod = {glm::vec3(-141.9f, 0.5f, 0.5f), 100.0f, 0.9931f};
  const DrawList list = cluster_draw_list(layout, layout.fine, all_units(layout), nullptr, &lod);
  EXPECT_EQ(list.units, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(list.triangles, 2u);
  EXPECT_EQ(triangles_of(layout, layout.fine, all_units(layout), &lod), 2u) << "the same count";
  EXPECT_EQ(triangles_of(layout, layout.fine, all_units(layout), nullptr), 4u);
}

// Two clusters of two squares each (the squares' coarse form is their fine form) with one level of detail
// each: one triangle, error 0.1 m.
TEST(ClusterLayout, LevelsOfDetailArePickedByProjectedErrorAndDrawnFromDenseVertexRuns) {
  Scene s({R::Opaque, R::Opaque, R::Opaque, R::Opaque});
  s.cluster({0, 1});
  s.cluster({2, 3});
  std::vector<model::CoarseRangeRecord> coarse;
  for (const auto& p : s.polygons) coarse.push_back({p.first_index, p.index_count});
  std::vector<std::uint32_t> lod_indices;
  std::vector<model::LodRangeRecord> lod_ranges;
  for (std::uint32_t k = 0; k < 2; ++k) {
    const std::uint32_t v = s.polygons[k * 2].first_vertex;  // a triangle over the cluster's first square
    lod_ranges.push_back({std::uint32_t(lod_indices.size()), 3, 0.1f, 0});
    lod_indices.insert(lod_indices.end(), {v, v + 1, v + 2});
    for (std::uint32_t l = 1; l < model::kLodLevels; ++l) lod_ranges.push_back({0, 0, 0.0f, 0});
  }
  LayoutInput in = s.input();
  in.coarse_ranges = coarse;
  in.coarse_indices = s.indices;
  in.lod_ranges = lod_ranges;
  in.lod_indices = lod_indices;
  const ClusterLayout layout = lay_out_clusters(in);
  const LaidOutForm& form = layout.coarse;
  ASSERT_EQ(form.lod.size(), 2u);
  EXPECT_EQ(form.lod[0][0].count, 3u);
  EXPECT_EQ(form.lod[0][1].first, form.lod[0][0].first) << "a missing level repeats the one before";
  EXPECT_FLOAT_EQ(form.lod_error[0][2], 0.1f);
  EXPECT_EQ(form.lod[1][0].first, form.lod[0][0].first + 3) << "one level's units side by side";

  // Each region's vertices are numbered by first use: cluster 0's level uses three of the four vertices
  // of its first square, which come first in the level's own run after the coarse form's 16 vertices
  // (rotated so the triangle ends on the vertex it was made from first).
  EXPECT_EQ(form.vertices.size(), 16u + 6u);
  EXPECT_EQ(form.indices[form.lod[0][0].first], 17u);
  EXPECT_EQ(form.indices[form.lod[0][0].first + 1], 18u);
  EXPECT_EQ(form.indices[form.lod[0][0].first + 2], 16u);
  for (std::size_t v = 0; v < form.vertices.size(); ++v) EXPECT_LT(form.vertices[v], s.vertices.size());

  // 60 degrees over 600 pixels: 0.1 m spans 1 pixel at 0.1 * 600 / (pi / 3) = 57 m.
  LodChoice lod{glm::vec3(-100.0f, 0.5f, 0.5f), float(600.0 / (3.14159265 / 3.0)), 1.0f};
  EXPECT_EQ(lod_level(layout, form, 0, lod), model::kLodLevels) << "100 m away: the coarsest";
  lod.eye = {-10.0f, 0.5f, 0.5f};
  EXPECT_EQ(lod_level(layout, form, 0, lod), 0) << "10 m away: its own form";
  lod.max_pixels = 10.0f;
  EXPECT_EQ(lod_level(layout, form, 0, lod), model::kLodLevels) << "a budget of 10 pixels allows it";
  const DrawList list = cluster_draw_list(layout, form, all_units(layout), nullptr, &lod);
  EXPECT_EQ(list.triangles, 2u);
  ASSERT_EQ(list.opaque.counts.size(), 1u) << "both clusters at one level meet";
  lod.max_pixels = 0.0f;
  EXPECT_EQ(cluster_draw_list(layout, form, all_units(layout), nullptr, &lod).triangles, 8u);
}

// A fan of single-triangle polygons round a grid point, as Sibenik's meshes are: the coarse form shares
// their corners, keeps each triangle's corners and winding (a rotation of them), and ends each triangle on
// a vertex of its own polygon, whose flat light it shows. A corner one float step away shares nothing.
TEST(ClusterLayout, CoarsePolygonsShareCornersAndEachTriangleEndsOnItsOwnPolygon) {
  // A 3 x 3 grid of points at z = 0, two triangles a square, each triangle a polygon; then one more
  // triangle whose first corner is one float step off grid point 4.
  std::vector<model::VertexRecord> vertices;
  std::vector<model::PolygonRecord> polygons;
  std::vector<std::uint32_t> indices;
  auto point = [](float x, float y) {
    model::VertexRecord v{};
    v.position[0] = x, v.position[1] = y;
    return v;
  };
  auto triangle = [&](model::VertexRecord a, model::VertexRecord b, model::VertexRecord c) {
    model::PolygonRecord p{};
    p.first_index = std::uint32_t(indices.size());
    p.index_count = 3;
    p.first_vertex = std::uint32_t(vertices.size());
    p.vertex_count = 3;
    p.role = std::uint32_t(R::Opaque);
    for (model::VertexRecord v : {a, b, c}) {
      v.polygon = std::uint32_t(polygons.size());
      indices.push_back(std::uint32_t(vertices.size()));
      vertices.push_back(v);
    }
    polygons.push_back(p);
  };
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const float fx = float(x), fy = float(y);
      triangle(point(fx, fy), point(fx + 1, fy), point(fx + 1, fy + 1));
      triangle(point(fx, fy), point(fx + 1, fy + 1), point(fx, fy + 1));
    }
  triangle(point(std::nextafter(1.0f, 2.0f), 1.0f), point(2.0f, 2.0f), point(1.0f, 2.0f));
  std::vector<model::CoarseRangeRecord> coarse;
  for (const auto& p : polygons) coarse.push_back({p.first_index, p.index_count});
  // One cluster holds them all: vertices are shared within a unit's range.
  std::vector<model::ClusterRecord> clusters(1);
  clusters[0].polygon_count = std::uint32_t(polygons.size());
  std::vector<std::uint32_t> members(polygons.size());
  std::iota(members.begin(), members.end(), 0u);
  const LayoutInput in{polygons, vertices, indices, coarse, indices, clusters, members, {}, {}};

  auto position = [&](const LaidOutForm& form, std::uint32_t index) {
    const float* p = vertices[form.vertices[form.indices[index]]].position;
    return std::array<float, 3>{p[0], p[1], p[2]};
  };
  for (const CoarseVertices how : {CoarseVertices::Shared, CoarseVertices::OwnPerPolygon}) {
    const LaidOutForm form = lay_out_clusters(in, how).coarse;
    for (std::uint32_t p = 0; p < polygons.size(); ++p) {
      const auto& laid = form.polygons[p];
      ASSERT_EQ(laid.index_count, 3u);
      // The laid-out corners are the source corners rotated by some r: same points, same winding.
      bool rotation = false;
      for (std::uint32_t r = 0; r < 3 && !rotation; ++r) {
        rotation = true;
        for (std::uint32_t i = 0; i < 3; ++i) {
          const float* source = vertices[indices[polygons[p].first_index + (i + r) % 3]].position;
          rotation = rotation && position(form, laid.first_index + i) ==
                                     std::array<float, 3>{source[0], source[1], source[2]};
        }
      }
      EXPECT_TRUE(rotation) << "polygon " << p;
      EXPECT_EQ(vertices[form.vertices[form.indices[laid.first_index + 2]]].polygon, p)
          << "the provoking (last) vertex carries its own polygon's light";
    }
    if (how == CoarseVertices::OwnPerPolygon) {
      EXPECT_EQ(form.vertices.size(), 27u) << "three vertices a triangle";
      continue;
    }
    // 9 triangles need 9 provoking vertices; the grid has 9 points, of which the last triangle, off by a
    // float step, can share two; its off corner is a vertex of its own.
    EXPECT_EQ(form.vertices.size(), 10u);
    std::set<std::array<float, 3>> points;
    for (std::uint32_t v : form.vertices) {
      const float* p = vertices[v].position;
      points.insert({p[0], p[1], p[2]});
    }
    EXPECT_EQ(points.size(), 10u) << "the off corner is not shared with grid point 4";
  }
  // Without the cluster each polygon is a unit of its own, and units share nothing: a unit's range spans
  // only its own vertices.
  const LayoutInput apart{polygons, vertices, indices, coarse, indices, {}, {}, {}, {}};
  EXPECT_EQ(lay_out_clusters(apart).coarse.vertices.size(), 27u);
}

}  // namespace cluster_layout_test
}  // namespace walk::render
