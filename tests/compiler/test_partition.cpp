// Airey's partition priority and the subdivision it drives.
#include <gtest/gtest.h>

#include <algorithm>

#include "compiler/partition/partition.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_partition {  // named, not anonymous: the suite compiles as unity batches

using testing::MiniBuilding;

std::vector<VisPolygon> polys(const MiniBuilding& m) {
  return vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
}

// Two 4x4x3 rooms side by side along x, sharing the wall x = 4 (with a 1x2 door when `door`).
MiniBuilding two_rooms(bool door) {
  MiniBuilding m;
  m.row_shell(8.0);
  if (door)
    m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);
  else
    m.rect(0, 4.0, 0, 4, 0, 3);
  return m;
}

TEST(Partition, AxialPlanesGroupCoplanarPolygons) {
  const auto p = polys(two_rooms(true));
  const auto planes = axial_planes(p);
  const AxialPlane* wall = find_plane(planes, 0, 4.0);
  ASSERT_NE(wall, nullptr);
  EXPECT_EQ(wall->opaque.size(), 3u);  // jamb sides and lintel of the door wall
  EXPECT_EQ(find_plane(planes, 0, 4.5), nullptr);
}

// A hall 12.5 m long, its length full of small panels, its far end behind a wall at `wall_x`, 60 % wall
// (a wide door).
MiniBuilding hall_with_panels(double wall_x) {
  MiniBuilding m;
  m.row_shell(12.5);
  m.rect_with_hole(0, wall_x, 0, 4, 0, 3, 0.8, 3.2, 0.0, 2.0);
  for (const double y : {0.5, 1.5, 2.5, 3.5})
    for (int i = 0; i < 10; ++i) m.rect(1, y, 0.0, 1.0, 0.5 + i, 1.0 + i);  // panels (u = z, v = x)
  return m;
}

// The hall's far end a 1.5 m room: the wall's plane has few polygons beyond it (poor balance) and scores
// under the threshold, yet it is mostly wall, and a wall between rooms divides them into cells.
TEST(Partition, APlaneMostlyWallSplitsWhateverItsBalance) {
  const auto p = polys(hall_with_panels(11.0));
  const auto planes = axial_planes(p);
  std::vector<std::uint32_t> ids(p.size());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  const VisibilityConfig cfg;
  const PlaneScore wall =
      score_plane(*find_plane(planes, 0, 11.0), Box{{0, 0, 0}, {12.5, 4, 3}}, ids, p, cfg);
  EXPECT_NEAR(wall.occlusion, 0.6, 1e-6);
  EXPECT_LT(wall.priority, cfg.threshold) << "balance " << wall.balance << " split " << wall.split;
  const Partition part = build_partition(p, cfg);
  EXPECT_NE(locate(part.nodes, {10.5, 2.0, 1.0}), locate(part.nodes, {11.5, 2.0, 1.0}))
      << part.cells.size() << " cells";
  // A plane that would leave less than a metre beyond it is a face of clutter, not a wall between rooms.
  const Partition whole = build_partition(polys(hall_with_panels(11.7)), cfg);  // 0.8 m before the end
  EXPECT_EQ(locate(whole.nodes, {11.5, 2.0, 1.0}), locate(whole.nodes, {12.0, 2.0, 1.0}));
}

TEST(Partition, OcclusionIsTheCoveredFraction) {
  const auto p = polys(two_rooms(true));
  const auto planes = axial_planes(p);
  const Box all{{0, 0, 0}, {8, 4, 3}};
  EXPECT_NEAR(occlusion_fraction(*find_plane(planes, 0, 4.0), all, p), 1.0 - 2.0 / 12.0, 1e-6);
  EXPECT_NEAR(occlusion_fraction(*find_plane(planes, 0, 0.0), all, p), 1.0, 1e-6);
  // A cell beside the plane's polygons: nothing covers its cross-section.
  EXPECT_NEAR(occlusion_fraction(*find_plane(planes, 0, 4.0), Box{{0, 10, 0}, {8, 14, 3}}, p), 0.0, 1e-12);
  AxialPlane empty{0, 4.0, {}, {}};
  EXPECT_EQ(occlusion_fraction(empty, all, p), 0.0);
}

TEST(Partition, PriorityWeighsOcclusionBalanceAndSplits) {
  const auto p = polys(two_rooms(false));
  const auto planes = axial_planes(p);
  const Box all{{0, 0, 0}, {8, 4, 3}};
  std::vector<std::uint32_t> ids(p.size());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  VisibilityConfig cfg;
  const PlaneScore s = score_plane(*find_plane(planes, 0, 4.0), all, ids, p, cfg);
  EXPECT_NEAR(s.occlusion, 1.0, 1e-6);
  EXPECT_NEAR(s.balance, 1.0, 1e-12);            // floor, ceiling, y walls split: 6 each side
  EXPECT_NEAR(s.split, 1.0 - 4.0 / 7.0, 1e-12);  // 4 of 7 polygons cross x = 4
  EXPECT_NEAR(s.priority, 0.5 + 0.3 + 0.2 * (3.0 / 7.0), 1e-6);
  const PlaneScore none = score_plane(*find_plane(planes, 0, 4.0), all, {}, p, cfg);
  EXPECT_EQ(none.balance, 0.0);  // no polygons: no balance, nothing split
  EXPECT_EQ(none.split, 1.0);
}

TEST(Partition, SplitsAtTheDividingWallIntoTwoCells) {
  const auto p = polys(two_rooms(true));
  const Partition part = build_partition(p, VisibilityConfig{});
  ASSERT_EQ(part.cells.size(), 2u);
  ASSERT_EQ(part.nodes.size(), 1u);
  EXPECT_DOUBLE_EQ(part.nodes[0].plane[0], 1.0);
  EXPECT_DOUBLE_EQ(part.nodes[0].plane[3], -4.0);
  EXPECT_NE(locate(part.nodes, {1, 1, 1}), locate(part.nodes, {7, 1, 1}));
  for (std::uint32_t c = 0; c < part.cells.size(); ++c) {
    const auto& b = part.cells[c];
    EXPECT_EQ(locate(part.nodes, (b.min + b.max) * 0.5), c);
  }
}

// Which cells list a polygon: those it reaches into, and both for one lying in the splitting plane; a polygon
// that only touches the plane along an edge stays on its own side (it cannot be seen from the other).
TEST(Partition, PolygonsTouchingTheSplitAlongAnEdgeStayOnTheirSide) {
  MiniBuilding m = two_rooms(false);
  const auto shelf = m.rect(2, 1.0, 2, 4, 1, 3);     // horizontal, x 2..4: its edge x = 4 is on the split
  const auto picture = m.rect(1, 0.01, 1, 2, 5, 7);  // y = 0.01, x 5..7: wholly in the second room
  const auto across = m.rect(2, 0.5, 3, 5, 1, 3);    // horizontal, x 3..5: reaches into both
  const auto p = polys(m);
  const Partition part = build_partition(p, VisibilityConfig{});
  ASSERT_EQ(part.cells.size(), 2u);
  const std::uint32_t first = locate(part.nodes, {1, 1, 1}), second = 1 - first;
  auto lists = [&](std::uint32_t cell, std::uint32_t polygon) {
    const auto& ids = part.cell_polygons[cell];
    return std::find(ids.begin(), ids.end(), polygon) != ids.end();
  };
  EXPECT_TRUE(lists(first, shelf));
  EXPECT_FALSE(lists(second, shelf)) << "touches x = 4 along an edge only";
  EXPECT_FALSE(lists(first, picture));
  EXPECT_TRUE(lists(second, picture));
  EXPECT_TRUE(lists(first, across) && lists(second, across));
  std::uint32_t wall = 0;  // the dividing wall lies in the plane: both rooms see it
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (p[i].axis == 0 && p[i].coord == 4.0) wall = i;
  EXPECT_TRUE(lists(first, wall) && lists(second, wall));
}

TEST(Partition, ThresholdAndDepthStopTheRecursion) {
  const auto p = polys(two_rooms(true));
  VisibilityConfig high;
  high.threshold = 0.99;
  EXPECT_EQ(build_partition(p, high).cells.size(), 2u) << "a wall with a door is mostly wall: it splits";
  MiniBuilding arch;  // the two rooms, the wall between them an arch: 37.5 % wall
  arch.row_shell(8.0);
  arch.rect_with_hole(0, 4.0, 0, 4, 0, 3, 0.5, 3.5, 0.0, 2.5);
  EXPECT_EQ(build_partition(polys(arch), high).cells.size(), 1u);
  VisibilityConfig shallow;
  shallow.max_depth = 0;
  const Partition one = build_partition(p, shallow);
  EXPECT_EQ(one.cells.size(), 1u);
  EXPECT_TRUE(one.nodes.empty());
  EXPECT_EQ(build_partition({}, VisibilityConfig{}).cells.size(), 1u);  // empty model: one cell
}

TEST(Partition, ChildrenPointForward) {
  MiniBuilding m = two_rooms(true);
  m.rect(1, 2.0, 0, 3, 0, 4);  // a second wall, y = 2, in the first room
  const auto part = build_partition(polys(m), VisibilityConfig{});
  EXPECT_GE(part.cells.size(), 3u);
  for (std::size_t n = 0; n < part.nodes.size(); ++n)
    for (const auto child : {part.nodes[n].front, part.nodes[n].back})
      if (child >= 0) {
        EXPECT_GT(std::size_t(child), n);
      }
}

}  // namespace test_partition
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_partition {  // named, not anonymous: the suite compiles as unity batches

TEST(Partition, BackToBackFacesCoverOnce) {
  // A floor facing up and the ceiling below it facing down, in one plane: opposite windings must not cancel.
  testing::MiniBuilding m;
  m.quad({0, 0, 3}, {4, 0, 3}, {4, 4, 3}, {0, 4, 3});
  m.quad({0, 0, 3}, {0, 4, 3}, {4, 4, 3}, {4, 0, 3});
  const auto p = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  const auto planes = axial_planes(p);
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_NEAR(occlusion_fraction(planes[0], Box{{0, 0, 0}, {4, 4, 6}}, p), 1.0, 1e-9);
}

}  // namespace test_partition
}  // namespace walk::compiler
