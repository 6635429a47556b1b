// Solids in the cells stage: their sections by axial planes, and cells split into the open regions they
// leave (open_regions.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <regex>
#include <string>

#include "compiler/partition/axial_cover.hpp"
#include "compiler/partition/solid_volumes.hpp"
#include "compiler/visibility/open_regions.hpp"
#include "compiler/visibility/verify_visibility.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_solid_regions {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
using testing::MiniBuilding;

// A prism over the convex counter-clockwise polygon `base` (x, y) from z0 to z1, faces wound outward.
model::Solid prism(const std::vector<std::array<double, 2>>& base, double z0, double z1) {
  model::Solid s;
  std::vector<Vec3> bottom, top;
  for (const auto& p : base) top.push_back({p[0], p[1], z1});
  for (auto it = base.rbegin(); it != base.rend(); ++it) bottom.push_back({(*it)[0], (*it)[1], z0});
  s.faces.push_back(bottom);
  s.faces.push_back(top);
  for (std::size_t i = 0; i < base.size(); ++i) {
    const auto& a = base[i];
    const auto& b = base[(i + 1) % base.size()];
    s.faces.push_back({{a[0], a[1], z0}, {b[0], b[1], z0}, {b[0], b[1], z1}, {a[0], a[1], z1}});
  }
  return s;
}

model::Solid box_solid(Vec3 lo, Vec3 hi) {
  return prism({{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}}, lo.z, hi.z);
}

double section_area(const SolidVolume& s, int axis, double coord) {
  const auto path = solid_section(s, axis, coord);
  return path.empty() ? 0.0 : ClipperLib::Area(path) / (kAxialClipperScale * kAxialClipperScale);
}

TEST(SolidVolumes, SectionsAndContainmentIncludingDegenerateContacts) {
  const auto solids = solid_volumes(std::vector{box_solid({0, 0, 0}, {1, 2, 3})});
  ASSERT_EQ(solids.size(), 1u);
  const SolidVolume& s = solids[0];
  EXPECT_EQ(s.planes.size(), 6u);
  EXPECT_NEAR(section_area(s, 0, 0.5), 6.0, 1e-9);  // through it: 2 x 3, counter-clockwise
  EXPECT_NEAR(section_area(s, 2, 1.0), 2.0, 1e-9);
  EXPECT_NEAR(section_area(s, 0, 1.0), 6.0, 1e-9);  // on a face: the face
  EXPECT_EQ(section_area(s, 0, 1.5), 0.0);          // past it
  // A diamond prism meets the plane x = 1 along one vertical edge only: no area, no section.
  const auto diamond = solid_volumes(std::vector{prism({{0, 0}, {1, 1}, {0, 2}, {-1, 1}}, 0, 1)});
  ASSERT_EQ(diamond.size(), 1u);
  EXPECT_TRUE(solid_section(diamond[0], 0, 1.0).empty());
  EXPECT_NEAR(section_area(diamond[0], 0, 0.5), 1.0, 1e-9);  // y 0.5..1.5 x z 0..1
  EXPECT_TRUE(solid_contains(s, {0.5, 1.0, 1.5}, 0.0));
  EXPECT_TRUE(solid_contains(s, {1.0, 1.0, 1.5}, 0.0));  // on a face
  EXPECT_TRUE(solid_contains(s, {1.0 + 5e-6, 1.0, 1.5}, kPlaneEpsilon));
  EXPECT_FALSE(solid_contains(s, {1.001, 1.0, 1.5}, kPlaneEpsilon));
  // A face without area is left out; four faces at least enclose something.
  model::Solid flat;
  flat.faces = {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}};
  EXPECT_TRUE(solid_volumes(std::vector{flat}).empty());
}

// Two rooms, 4 m and 4 m, on either side of a 0.4 m wall that one cell straddles (no split keeps the
// model one cell). `gap` opens a 1 m doorway through the wall; `seam` builds the wall of two wedges meeting
// along a slanted plane, which no voxel lies wholly inside one of.
struct TwoRooms {
  MiniBuilding m;
  std::vector<model::Solid> solids;
  TwoRooms(bool gap, bool seam) {
    m.room_inward({0, 0, 0}, {4, 4, 3});
    m.room_inward({4.4, 0, 0}, {8.4, 4, 3});
    if (gap) {
      solids.push_back(box_solid({4, 0, 0}, {4.4, 1.5, 3}));
      solids.push_back(box_solid({4, 2.5, 0}, {4.4, 4, 3}));
    } else if (seam) {
      solids.push_back(prism({{4, 0}, {4.4, 0}, {4.1, 4}, {4, 4}}, 0, 3));
      solids.push_back(prism({{4.4, 0}, {4.4, 4}, {4.1, 4}}, 0, 3));
    } else {
      solids.push_back(box_solid({4, 0, 0}, {4.4, 4, 3}));
    }
  }
  VisibilityResult compute() const {
    VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
    c.max_depth = 0;  // one cell
    c.solids = solid_volumes(solids);
    c.seeds = {{2, 2, 1.5}};
    return compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c);
  }
};

bool sees_room_b(const VisibilityResult& r) {
  // Room B's polygons are the last six; its wall facing room A (x = 4.4, facing +x) among them.
  const auto pvs = r.polygon_pvs(0);
  return std::any_of(pvs.begin(), pvs.end(), [](std::uint32_t p) { return p >= 6; });
}

TEST(OpenRegions, AWallInsideOneCellSplitsItAndTheFarRoomLeavesThePvs) {
  const VisibilityResult r = TwoRooms(false, false).compute();
  ASSERT_EQ(r.partition.cells.size(), 1u);
  EXPECT_EQ(r.regions, 2u);
  EXPECT_EQ(r.inside[0], 1);
  EXPECT_EQ(r.polygon_pvs(0).size(), 6u);  // room A's six faces
  EXPECT_FALSE(sees_room_b(r));
  // Without solids the cell is convex open space and sees both rooms.
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.max_depth = 0;
  const TwoRooms plain(false, false);
  const VisibilityResult open =
      compute_visibility(plain.m.b.vertices, plain.m.b.indices, plain.m.b.polygons, c);
  EXPECT_EQ(open.regions, 0u);
  EXPECT_TRUE(sees_room_b(open));
}

TEST(OpenRegions, AFaceAFewMicrometresInsideItsSolidStaysInItsRoom) {
  // Bundle faces are float, solids double: room A's wall face (x = 4) lies 4 um inside a wall solid that
  // starts at 4 - 4e-6. It is still room A's, and in its PVS.
  TwoRooms rooms(false, false);
  rooms.solids = {box_solid({4 - 4e-6, 0, 0}, {4.4, 4, 3})};
  const VisibilityResult r = rooms.compute();
  EXPECT_EQ(r.regions, 2u);
  const auto pvs = r.polygon_pvs(0);
  EXPECT_TRUE(std::binary_search(pvs.begin(), pvs.end(), 1u));  // room A's x = 4 face
  EXPECT_EQ(pvs.size(), 6u);
}

TEST(OpenRegions, ADoorwayJoinsTheRooms) {
  const VisibilityResult r = TwoRooms(true, false).compute();
  EXPECT_EQ(r.regions, 1u);
  EXPECT_TRUE(sees_room_b(r));
}

TEST(OpenRegions, SolidsMeetingAlongASlantedSeamLeaveNoOpening) {
  const VisibilityResult r = TwoRooms(false, true).compute();
  EXPECT_EQ(r.regions, 2u);
  EXPECT_FALSE(sees_room_b(r));
}

TEST(OpenRegions, PortalsLoseThePartsInsideSolids) {
  // Two cells split at x = 4.2 (a wall face in that plane makes it the best candidate), the wall solid
  // across it: the face between the cells lies wholly inside the wall, so no portal joins them.
  TwoRooms rooms(false, false);
  rooms.m.rect(0, 4.2, 0, 0.1, 0, 0.1);  // a small face in the plane, so the plane is a candidate
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.threshold = 0.0;
  c.max_depth = 1;
  const auto plain = compute_visibility(rooms.m.b.vertices, rooms.m.b.indices, rooms.m.b.polygons, c);
  c.solids = solid_volumes(rooms.solids);
  const auto solid = compute_visibility(rooms.m.b.vertices, rooms.m.b.indices, rooms.m.b.polygons, c);
  ASSERT_EQ(plain.partition.cells.size(), solid.partition.cells.size());
  EXPECT_LT(solid.graph.portals.size(), plain.graph.portals.size());
  for (const auto& p : solid.graph.portals) {
    if (p.axis == 0 && std::abs(p.coord - 4.2) < 1e-9) {
      ADD_FAILURE() << "a portal inside the wall";
    }
  }
}

TEST(OpenRegions, ASolidEndingMicrometresShortOfAFaceClosesIt) {
  // Two cells meeting at x = 4.2 and a wall across them made of two solids that stop 2 um either side of
  // that plane (a bundle face and a model's solid apart by float noise): sectioned at the plane itself,
  // neither would close the face. Solids 0.1 m from it leave a real gap, and a portal.
  Partition part;
  part.cells = {Box{{0, 0, 0}, {4.2, 4, 3}}, Box{{4.2, 0, 0}, {8.4, 4, 3}}};
  part.bounds = Box{{0, 0, 0}, {8.4, 4, 3}};
  const std::vector<VisPolygon> none;
  const auto portals_at = [&](double gap) {
    const auto solids = solid_volumes(
        std::vector{box_solid({4, 0, 0}, {4.2 - gap, 4, 3}), box_solid({4.2 + gap, 0, 0}, {4.4, 4, 3})});
    return find_portals(part, none, true, solids).portals.size();
  };
  EXPECT_EQ(portals_at(2e-6), 0u);
  EXPECT_EQ(portals_at(0.1), 1u);
}

TEST(OpenRegions, TheFacesOfASealedShellTowardsTheVoidAreVoidFacing) {
  // A 4 x 4 x 3 m room inside a shell of 0.2 m solid walls, and a solid pillar 3.8 m beyond it, so the
  // model's box holds void between them. The shell's faces are drawn both ways: into the room and out.
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {4, 4, 3});
  const auto first_outer = static_cast<std::uint32_t>(m.b.polygons.size());
  const auto outward_box = [&m](const Vec3& lo, const Vec3& hi) {
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      m.rect(a, lo[a], lo[u], hi[u], lo[v], hi[v], model::Role::Opaque, -1);
      m.rect(a, hi[a], lo[u], hi[u], lo[v], hi[v], model::Role::Opaque, 1);
    }
  };
  outward_box({-0.2, -0.2, -0.2}, {4.2, 4.2, 3.2});
  outward_box({8, 1, 0}, {9, 2, 3});
  const auto end = static_cast<std::uint32_t>(m.b.polygons.size());
  const std::vector<model::Solid> solids{box_solid({-0.2, -0.2, -0.2}, {4.2, 4.2, 0}),
                                         box_solid({-0.2, -0.2, 3}, {4.2, 4.2, 3.2}),
                                         box_solid({-0.2, -0.2, 0}, {0, 4.2, 3}),
                                         box_solid({4, -0.2, 0}, {4.2, 4.2, 3}),
                                         box_solid({0, -0.2, 0}, {4, 0, 3}),
                                         box_solid({0, 4, 0}, {4, 4.2, 3}),
                                         box_solid({8, 1, 0}, {9, 2, 3})};
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.solids = solid_volumes(solids);
  c.seeds = {{2, 2, 1.5}};
  const VisibilityResult r = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c);
  EXPECT_TRUE(r.leaks.empty());
  const std::vector<std::uint32_t> void_polygons = r.polygons_of(r.void_facing);
  std::vector<std::uint32_t> outer;
  for (std::uint32_t p = first_outer; p < end; ++p) outer.push_back(p);
  // The shell's outside and the pillar (faces on the model's box face out of it), not the room's faces.
  EXPECT_EQ(void_polygons, outer);
  // The judge takes a point in the void for open space unless it knows the faces there face the void.
  const VisibilityJudge plain(m.b.vertices, m.b.indices, m.b.polygons, testing::small_judge(true));
  const VisibilityJudge sealed(m.b.vertices, m.b.indices, m.b.polygons, testing::small_judge(true),
                               void_polygons);
  EXPECT_TRUE(plain.in_free_space({4.6, 2, 1.5}));
  EXPECT_FALSE(sealed.in_free_space({4.6, 2, 1.5}));
  EXPECT_TRUE(sealed.in_free_space({2, 2, 1.5}));
}

TEST(OpenRegions, ADetailClusterSetInTheCeilingIsSeenFromTheRoomBelow) {
  // A room whose ceiling (z = 3) has a 0.2 m hole filled by the bottom face of a fixture set into the slab
  // above: the fixture is detail, its box rests on the plane the cells split at, so only the cell above
  // lists it, and that cell's open part is all slab (solid). Seen from the room, it must be in its PVS.
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {4, 4, 3});
  m.b.polygons.erase(m.b.polygons.begin() + 5);  // the ceiling (the sixth face: z = 3, facing down)...
  m.b.indices.resize(m.b.polygons.back().first_index + m.b.polygons.back().index_count);
  m.b.vertices.resize(m.b.polygons.back().first_vertex + m.b.polygons.back().vertex_count);
  for (const auto& [u0, u1, v0, v1] : std::vector<std::array<double, 4>>{
           {0, 1.9, 0, 4}, {2.1, 4, 0, 4}, {1.9, 2.1, 0, 1.9}, {1.9, 2.1, 2.1, 4}})
    m.rect(2, 3.0, u0, u1, v0, v1, model::Role::Opaque, -1);  // ...rebuilt round the hole
  const auto first_fixture = static_cast<std::uint32_t>(m.b.polygons.size());
  m.rect(2, 3.0, 1.9, 2.1, 1.9, 2.1, model::Role::Opaque, -1);  // the fixture's face in the hole
  m.rect(2, 3.2, 1.9, 2.1, 1.9, 2.1, model::Role::Opaque, 1);   // and its top, inside the slab
  for (std::uint32_t p = first_fixture; p < m.b.polygons.size(); ++p) m.b.polygons[p].group = 1;
  const std::vector<std::string> groups{"room", "fixture"};
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.threshold = 0.3;
  c.max_depth = 1;
  c.detail_groups = std::regex("fixture");
  c.solids = solid_volumes(std::vector{box_solid({0, 0, 3}, {4, 4, 3.4})});
  c.seeds = {{2, 2, 1.5}};
  const VisibilityResult r = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c, groups);
  ASSERT_EQ(r.partition.cells.size(), 2u);
  const std::uint32_t below = r.partition.cells[0].max.z <= 3.0 + 1e-9 ? 0 : 1;
  ASSERT_LE(r.partition.cells[below].max.z, 3.0 + 1e-9);
  const auto pvs = r.polygon_pvs(below);
  EXPECT_TRUE(std::binary_search(pvs.begin(), pvs.end(), first_fixture));
}

TEST(OpenRegions, SpaceTouchingTheRoomOnlyAlongAnEdgeStaysApart) {
  // A 4 x 4 m room, one cell. A low wall (x 1.5..2, y 0..1.5) and a sloping block (its underside the line
  // y = x - 0.5 from the wall's corner (2, 1.5) to the far wall) leave the room's corner below the slope and
  // the rest of it touching only along the wall's top edge: no sight line passes from one to the other.
  // Voxels just right of that edge hold open space under the slope; their faces towards the wall's side lie
  // in the block, so the two parts stay apart.
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {4, 4, 3});
  const std::vector<model::Solid> solids{box_solid({1.5, 0, 0}, {2, 1.5, 3}),
                                         prism({{2, 1.5}, {4, 3.5}, {4, 4}, {2, 4}}, 0, 3)};
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.max_depth = 0;  // one cell
  c.solids = solid_volumes(solids);
  c.seeds = {{0.7, 2, 1.5}};
  const VisibilityResult r = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c);
  ASSERT_EQ(r.partition.cells.size(), 1u);
  EXPECT_EQ(r.regions, 2u);
}

TEST(OpenRegions, AnLShapedOpeningJoinsOnlyWhatLiesBehindIt) {
  // Two cells split at y = 2. Beyond it a block (x 2..4, z 0..1.5) closes the lower right of the face, so
  // the opening between the cells is L-shaped. Before it, walls and a lid close a pocket (x 2.4..4, y 1..2,
  // z 0..1.1) against the block: the pocket lies within the opening's box but behind no part of it, and
  // stays a region of its own.
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {4, 4, 3});
  m.rect(1, 2.0, 0, 1.5, 2, 4, model::Role::Opaque, -1);  // the block's face there (u = z, v = x)
  const std::vector<model::Solid> solids{
      box_solid({2, 2, 0}, {4, 2.4, 1.5}),    // the block beyond
      box_solid({2, 0.6, 0}, {2.4, 2, 1.5}),  // the pocket's side wall
      box_solid({2, 0.6, 0}, {4, 1, 1.5}),    // its front wall
      box_solid({2, 0.6, 1.1}, {4, 2, 1.5}),  // its lid
  };
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.threshold = 0.0;
  c.max_depth = 1;
  c.solids = solid_volumes(solids);
  c.seeds = {{1, 0.3, 1.5}};
  const VisibilityResult r = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c);
  ASSERT_EQ(r.partition.cells.size(), 2u);
  ASSERT_EQ(std::min(r.partition.cells[0].max.y, r.partition.cells[1].max.y), 2.0);
  EXPECT_EQ(r.regions, 3u);  // the room on each side, and the pocket
}

TEST(OpenRegions, AnOpeningEndingAtACorniceTopJoinsNotTheSpaceAboveIt) {
  // A 4 x 4 x 4 m room split into two cells at y = 2. A ceiling slab (x 0..3.5, z 3..3.4) and a cornice
  // along the x = 4 wall (its section the triangle (3.5, 3), (4, 3), (4, 2.5), top at z = 3) close a loft
  // above the room; they meet along one edge. The slab's solid starts 4 um above z = 3 (a bundle face and
  // its solid disagree by float noise), so the opening between the cells reaches 4 um past the grid line
  // at the cornice's top, over the voxels of the loft beyond the slab's end. No sight line passes there:
  // room and loft stay apart on both sides.
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {4, 4, 4});
  m.rect(1, 2.0, 0, 1, 0, 1);  // a panel in the plane y = 2, so the cells split there
  std::vector<model::Solid> solids{box_solid({0, 0, 3.0 + 4e-6}, {3.5, 4, 3.4})};
  // The cornice: a prism along y over the triangle in (x, z), faces wound outward.
  model::Solid cornice;
  const std::vector<std::array<double, 2>> tri{{3.5, 3.0}, {4.0, 2.5}, {4.0, 3.0}};  // clockwise in (x, z)
  std::vector<Vec3> front, back;
  for (const auto& p : tri) front.push_back({p[0], 0.0, p[1]});
  for (auto it = tri.rbegin(); it != tri.rend(); ++it) back.push_back({(*it)[0], 4.0, (*it)[1]});
  cornice.faces = {front, back};
  for (std::size_t i = 0; i < tri.size(); ++i) {
    const auto& a = tri[i];
    const auto& b = tri[(i + 1) % tri.size()];
    cornice.faces.push_back({{a[0], 0, a[1]}, {a[0], 4, a[1]}, {b[0], 4, b[1]}, {b[0], 0, b[1]}});
  }
  solids.push_back(cornice);
  VisibilityConfig c = testing::test_config(PvsMethod::Conservative, true);
  c.threshold = 0.0;
  c.max_depth = 1;
  c.solids = solid_volumes(solids);
  ASSERT_EQ(c.solids.size(), 2u);
  EXPECT_TRUE(solid_contains(c.solids[1], {3.9, 2.0, 2.9}, 0.0));   // the cornice, wound outward
  EXPECT_FALSE(solid_contains(c.solids[1], {3.6, 2.0, 2.6}, 0.0));  // the room below its slope
  c.seeds = {{1, 1, 1.5}};
  const VisibilityResult r = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, c);
  ASSERT_EQ(r.partition.cells.size(), 2u);
  ASSERT_EQ(std::min(r.partition.cells[0].max.y, r.partition.cells[1].max.y), 2.0);
  EXPECT_EQ(r.regions, 4u);  // the room and the loft in each cell
  EXPECT_TRUE(r.leaks.empty());
}

}  // namespace test_solid_regions
}  // namespace walk::compiler
