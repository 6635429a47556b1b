// Which polygons stand as occluders, and which of their edges another occluder closes: only large opaque
// polygons; a wall and the floor it stands on close their shared edge when they are wound as one surface,
// and not when one is turned the other way (then both facing the eye would lie on one side of the edge).
#include "render/occluders.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "model/model.hpp"
#include "render/cluster_layout.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace occluders_test {  // named, not anonymous: the suite compiles as unity batches

// Room A's floor is polygon 0, its wall at y = 0 polygon 2 (two_rooms.cpp).
constexpr std::uint32_t kFloorA = 0, kWallA = 2;

const OccluderSet::Polygon* find(const OccluderSet& set, std::uint32_t source, std::uint32_t* id = nullptr) {
  for (std::uint32_t i = 0; i < set.polygons.size(); ++i)
    if (set.polygons[i].source == source) {
      if (id) *id = i;
      return &set.polygons[i];
    }
  return nullptr;
}

// The partners of the floor's edge along y = 0, z = 0 (where the wall stands).
std::vector<std::uint32_t> floor_edge_partners(const OccluderSet& set) {
  const OccluderSet::Polygon* floor = find(set, kFloorA);
  EXPECT_NE(floor, nullptr);
  if (!floor) return {};
  for (std::uint32_t e = floor->edge_first; e < floor->edge_first + floor->edge_count; ++e) {
    const auto& edge = set.edges[e];
    const glm::vec3 a = set.corners[floor->corner_first + edge.a],
                    b = set.corners[floor->corner_first + edge.b];
    if (a.y == 0.0f && b.y == 0.0f)
      return {set.partners.begin() + edge.partner_first,
              set.partners.begin() + edge.partner_first + edge.partner_count};
  }
  ADD_FAILURE() << "the floor has no boundary edge along y = 0";
  return {};
}

TEST(Occluders, LargeOpaquePolygonsOnlyWithTheirBoundaryEdges) {
  TwoRooms scene;
  scene.crate = true;       // five faces of 0.25 m2: too small
  scene.glass_door = true;  // glass hides nothing
  auto bundle = open_two_rooms(scene, "occluders_large");
  const ClusterLayout layout = lay_out_clusters(layout_input(*bundle));
  const OccluderSet set = find_occluders(layout, bundle->vertices());
  // Per room: floor, ceiling, two side walls, the outer wall, three shared-wall pieces (the lintel, 1 x 0.8
  // m, is large enough).
  EXPECT_EQ(set.polygons.size(), 16u);
  for (const auto& p : set.polygons) {
    EXPECT_NE(bundle->polygons()[p.source].role, std::uint32_t(model::Role::Glass));
    EXPECT_EQ(p.triangle_count, 2u);
    EXPECT_EQ(p.edge_count, 4u) << "a rectangle's diagonal is inside it, its four sides its boundary";
  }
  EXPECT_EQ(set.unit_first.size(), layout.units() + 1);
}

TEST(Occluders, AWallClosesTheFloorsEdgeOnlyWhenWoundAsOneSurface) {
  {
    auto bundle = open_two_rooms(TwoRooms{}, "occluders_wound");
    const OccluderSet set = find_occluders(lay_out_clusters(layout_input(*bundle)), bundle->vertices());
    std::uint32_t wall = 0;
    ASSERT_NE(find(set, kWallA, &wall), nullptr);
    const auto partners = floor_edge_partners(set);
    EXPECT_NE(std::find(partners.begin(), partners.end(), wall), partners.end());
  }
  {
    // The same wall turned round (each triangle's winding reversed).
    model::BundleContents contents = make_two_rooms(TwoRooms{});
    const auto& wall = contents.polygons[kWallA];
    for (std::uint32_t i = wall.first_index; i + 2 < wall.first_index + wall.index_count; i += 3)
      std::swap(contents.indices[i + 1], contents.indices[i + 2]);
    auto bundle = open_bundle(contents, "occluders_turned");
    const OccluderSet set = find_occluders(lay_out_clusters(layout_input(*bundle)), bundle->vertices());
    std::uint32_t wall_id = 0;
    ASSERT_NE(find(set, kWallA, &wall_id), nullptr);
    const auto partners = floor_edge_partners(set);
    EXPECT_EQ(std::find(partners.begin(), partners.end(), wall_id), partners.end());
  }
}

}  // namespace occluders_test
}  // namespace walk::render::test
