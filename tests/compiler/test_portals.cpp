// Portals as real polygons, and the leak report.
#include <gtest/gtest.h>

#include <algorithm>

#include "compiler/partition/portals.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_portals {  // named, not anonymous: the suite compiles as unity batches

using testing::MiniBuilding;

// Cells no thinner than 0.5 m: a wall's slab is no cell of its own, and each door is one portal.
PortalGraph graph_of(const MiniBuilding& m, Partition* out = nullptr) {
  const auto p = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  VisibilityConfig config;
  config.min_cell_size = 0.5;
  Partition part = build_partition(p, config);
  PortalGraph g = find_portals(part, p);
  if (out) *out = std::move(part);
  return g;
}

// Two rooms along x divided by a wall of thickness `t` at x = 4 .. 4+t, with a 1x2 m door.
MiniBuilding door_in_wall(double t) {
  MiniBuilding m;
  m.row_shell(8.0 + t);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);
  if (t > 0.0) {
    m.rect_with_hole(0, 4.0 + t, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);
    m.rect(1, 1.5, 0, 2, 4, 4 + t);  // jambs (y = 1.5, 2.5) and head (z = 2)
    m.rect(1, 2.5, 0, 2, 4, 4 + t);
    m.rect(2, 2.0, 4, 4 + t, 1.5, 2.5);
  }
  return m;
}

TEST(Portals, DoorInAThinWallIsOnePortalOfTheDoorsSize) {
  Partition part;
  const PortalGraph g = graph_of(door_in_wall(0.1), &part);
  ASSERT_EQ(part.cells.size(), 2u);  // the 0.1 m wall slab is no cell of its own (min_cell_size)
  ASSERT_EQ(g.portals.size(), 1u);
  const Portal& p = g.portals[0];
  EXPECT_EQ(p.axis, 0);
  EXPECT_NEAR(p.area, 2.0, 1e-6);
  EXPECT_NE(p.back, p.front);
  EXPECT_EQ(p.hull.size(), 4u);
  EXPECT_FALSE(p.glazed);
  EXPECT_TRUE(g.leaks.empty());
}

TEST(Portals, ZeroThicknessWallDoor) {
  const PortalGraph g = graph_of(door_in_wall(0.0));
  ASSERT_EQ(g.portals.size(), 1u);
  EXPECT_NEAR(g.portals[0].area, 2.0, 1e-6);
}

TEST(Portals, OpeningsTouchingAtACornerAreTwoPortals) {
  // Two rooms along x; the wall between them (x = 4, (u, v) = (y, z)) is a slab over y 0..2, z 1..3, a
  // cornice's triangle (2, 1), (4, 1), (4, 0) and a panel over y 2..4, z 2..3. What stays open is the
  // opening under the slab and the cornice, and the gap y 2..4, z 1..2 above the cornice: they meet at the
  // single point (2, 1). As one portal they would join whatever lies behind each (with solids, a room and
  // the void beyond a cornice) though no sight line passes from one to the other.
  MiniBuilding m;
  m.row_shell(8.0);
  m.rect(0, 4.0, 0, 2, 1, 3);
  m.quad({4, 2, 1}, {4, 4, 0}, {4, 4, 1}, {4, 4, 1});  // the cornice's triangle
  m.rect(0, 4.0, 2, 4, 2, 3);
  Partition part;
  const PortalGraph g = graph_of(m, &part);
  ASSERT_EQ(part.cells.size(), 2u);
  ASSERT_EQ(g.portals.size(), 2u);
  std::vector<double> areas{g.portals[0].area, g.portals[1].area};
  std::sort(areas.begin(), areas.end());
  EXPECT_NEAR(areas[0], 2.0, 1e-6);  // the gap above the cornice
  EXPECT_NEAR(areas[1], 3.0, 1e-6);  // the opening below: 2 x 1 and the triangle under the cornice
}

TEST(Portals, SealedWallHasNoPortal) {
  MiniBuilding m;
  m.room({0, 0, 0}, {4, 4, 3});
  m.room({4, 0, 0}, {8, 4, 3});
  Partition part;
  const PortalGraph g = graph_of(m, &part);
  EXPECT_EQ(part.cells.size(), 2u);
  EXPECT_TRUE(g.portals.empty());
  EXPECT_TRUE(g.leaks.empty());
}

TEST(Portals, GlassIsSeeThroughButSealsLeaks) {
  // The shared wall has a 2x1 window of glass.
  MiniBuilding w;
  w.row_shell(8.0);
  w.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.0, 3.0, 1.0, 2.0);
  w.rect(0, 4.0, 1.0, 3.0, 1.0, 2.0, model::Role::Glass);
  const PortalGraph g = graph_of(w);
  ASSERT_EQ(g.portals.size(), 1u);
  EXPECT_NEAR(g.portals[0].area, 2.0, 1e-6);
  EXPECT_TRUE(g.portals[0].glazed);
}

TEST(Portals, HoleToTheOutsideIsALeakWithItsPlace) {
  MiniBuilding m;
  m.rect(2, 0.0, 0, 4, 0, 4);
  m.rect(2, 3.0, 0, 4, 0, 4);
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.0, 2.0, 1.0, 2.0);  // 1x1 hole in x = 4, at y 1..2, z 1..2
  m.rect(1, 0.0, 0, 3, 0, 4);
  m.rect(1, 4.0, 0, 3, 0, 4);
  const PortalGraph g = graph_of(m);
  ASSERT_EQ(g.leaks.size(), 1u);
  EXPECT_NEAR(g.leaks[0].area, 1.0, 1e-6);
  EXPECT_NEAR(g.leaks[0].where.x, 4.0, 1e-9);
  EXPECT_NEAR(g.leaks[0].where.y, 1.5, 1e-6);
  EXPECT_NEAR(g.leaks[0].where.z, 1.5, 1e-6);
  EXPECT_TRUE(g.leaks[0].max_side);
  // Glazing the hole seals it.
  m.rect(0, 4.0, 1.0, 2.0, 1.0, 2.0, model::Role::Glass);
  EXPECT_TRUE(graph_of(m).leaks.empty());
}

TEST(Portals, CracksFromRoundingAreNoPortals) {
  // The dividing wall as two pieces with a 50 um gap between them.
  MiniBuilding w;
  w.rect(2, 0.0, 0, 8, 0, 4);
  w.rect(2, 3.0, 0, 8, 0, 4);
  w.rect(0, 0.0, 0, 4, 0, 3);
  w.rect(0, 8.0, 0, 4, 0, 3);
  w.rect(1, 0.0, 0, 3, 0, 8);
  w.rect(1, 4.0, 0, 3, 0, 8);
  w.rect(0, 4.0, 0, 2.0, 0, 3);
  w.rect(0, 4.0, 2.00005, 4, 0, 3);
  EXPECT_TRUE(graph_of(w).portals.empty());
}

}  // namespace test_portals
}  // namespace walk::compiler
