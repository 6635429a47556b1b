// Structure and detail, clusters and the inside flood: what keeps the cells stage's cost in clusters and
// its cells in the building.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <numeric>
#include <regex>
#include <set>

#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/inside_flood.hpp"
#include "compiler/visibility/verify_visibility.hpp"
#include "compiler/visibility/vis_items.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_structure_detail {  // named, not anonymous: the suite compiles as unity batches

using testing::MiniBuilding;
using testing::test_config;

bool has(const std::vector<std::uint32_t>& v, std::uint32_t x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// Names the bundle's groups and puts polygons [first, end) in group `g`.
void name_groups(MiniBuilding& m, std::initializer_list<const char*> names) {
  m.b.groups.clear();
  for (const char* n : names) m.b.groups.push_back({m.b.add_string(n)});
}
void put_in_group(MiniBuilding& m, std::uint32_t first, std::uint32_t end, std::uint32_t g) {
  for (std::uint32_t p = first; p < end; ++p) m.b.polygons[p].group = g;
}
std::vector<std::string> group_names(const MiniBuilding& m) {
  std::vector<std::string> out;
  for (const auto& g : m.b.groups) out.emplace_back(m.b.strings.c_str() + g.name);
  return out;
}

// Two 4x4x3 rooms along x with a 1x2 door at x = 4 (y 1.5..2.5, z 0..2), walls facing into the rooms.
MiniBuilding two_rooms_with_a_door() {
  MiniBuilding m;
  m.rect(2, 0.0, 0, 8, 0, 4);
  m.rect(2, 3.0, 0, 8, 0, 4, model::Role::Opaque, -1);
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect(0, 8.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  m.rect(1, 0.0, 0, 3, 0, 8);
  m.rect(1, 4.0, 0, 3, 0, 8, model::Role::Opaque, -1);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);
  return m;
}

// A chair-sized object of many small quads: `n` x `n` tiles on each face of the box.
std::uint32_t tiled_box(MiniBuilding& m, model::Vec3 lo, model::Vec3 hi, int n) {
  const auto first = static_cast<std::uint32_t>(m.b.polygons.size());
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const double du = (hi[u] - lo[u]) / n, dv = (hi[v] - lo[v]) / n;
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k)
        for (const double at : {lo[a], hi[a]})
          m.rect(a, at, lo[u] + i * du, lo[u] + (i + 1) * du, lo[v] + k * dv, lo[v] + (k + 1) * dv);
  }
  return first;
}

TEST(StructureDetail, FurnitureTouchingADoorNeitherSplitsACellNorCoversThePortal) {
  MiniBuilding m = two_rooms_with_a_door();
  const auto shell_end = static_cast<std::uint32_t>(m.b.polygons.size());
  // A cabinet standing in the doorway's jamb, reaching through the door plane into both rooms.
  const std::uint32_t cabinet = tiled_box(m, {3.7, 1.3, 0.0}, {4.3, 1.9, 1.2}, 4);
  const auto end = static_cast<std::uint32_t>(m.b.polygons.size());
  name_groups(m, {"shell", "cabinet"});
  put_in_group(m, cabinet, end, 1);
  const VisibilityConfig config = test_config(PvsMethod::Combined, true);
  const VisibilityResult vis =
      compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config, group_names(m));
  EXPECT_EQ(vis.structure_items, shell_end) << "every wall is structure, no cabinet face is";
  EXPECT_EQ(vis.detail_polygons, end - cabinet);
  ASSERT_EQ(vis.partition.cells.size(), 2u) << "the cabinet's faces are no splitting planes";
  double door = 0.0;
  for (const auto& p : vis.graph.portals) door += p.forward && p.backward ? p.area : 0.0;  // not wall backs
  EXPECT_NEAR(door, 2.0, 1e-6) << "the door is open, the cabinet covers none of it";
  // The cabinet is in both rooms' PVS (it stands in both), and nothing seen is missed.
  for (std::uint32_t c = 0; c < 2; ++c) EXPECT_TRUE(has(vis.polygon_pvs(c), cabinet)) << "cell " << c;
  EXPECT_EQ(testing::missed_pixels(m, vis, {0, 1}, true), 0u);
}

TEST(StructureDetail, ASmallRoomOfWholeWallsIsStructureAnObjectOfFacetsIsNot) {
  MiniBuilding m;
  m.room({0, 0, 0}, {2.5, 2.0, 2.6});  // a washroom: six whole faces, its box under 3 m
  const auto object = tiled_box(m, {0.5, 0.5, 0}, {1.0, 1.0, 0.8}, 3);
  const auto end = static_cast<std::uint32_t>(m.b.polygons.size());
  name_groups(m, {"washroom", "bin"});
  put_in_group(m, object, end, 1);
  const auto polys = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  VisibilityConfig config;
  auto structure = structure_polygons(polys, m.b.polygons, group_names(m), config);
  for (std::uint32_t p = 0; p < end; ++p) EXPECT_EQ(structure[p] != 0, p < object) << "polygon " << p;

  // The scene's patterns decide first: the bin as structure, the washroom as detail.
  config.structure_groups = std::regex("^bin$");
  config.detail_groups = std::regex("wash");
  structure = structure_polygons(polys, m.b.polygons, group_names(m), config);
  for (std::uint32_t p = 0; p < end; ++p) EXPECT_EQ(structure[p] != 0, p >= object) << "polygon " << p;

  // Degenerate settings: no size rule at all keeps everything structure (the behaviour before detail).
  config = VisibilityConfig{};
  config.detail_extent = 0.0;
  config.detail_area = 0.0;
  structure = structure_polygons(polys, m.b.polygons, group_names(m), config);
  EXPECT_EQ(std::count(structure.begin(), structure.end(), 1), static_cast<std::ptrdiff_t>(end));
}

// A door through a hollow wall (two faces 0.2 m apart): its jambs and lintel are a small group of small
// faces, detail by size. As detail they split no cell, and the door's passage shares a cell with the wall's
// whole hollow core, through which sight lines creep on (on the generated M building up every storey's
// walls). Named a frame (the openings stage names the groups it cut doors for) they are structure, and the
// passage is a cell of its own, between the jambs and under the lintel.
TEST(StructureDetail, ADoorFrameInAHollowWallIsStructure) {
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {8.1, 4, 3});
  m.rect_with_hole(0, 3.9, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0, -1);  // room A's side of the wall, facing A
  m.rect_with_hole(0, 4.1, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);      // room B's side, facing B
  const auto frame = static_cast<std::uint32_t>(m.b.polygons.size());
  m.rect(1, 1.5, 0.0, 2.0, 3.9, 4.1);  // jambs (axis y: u = z, v = x), facing into the passage
  m.rect(1, 2.5, 0.0, 2.0, 3.9, 4.1, model::Role::Opaque, -1);
  m.rect(2, 2.0, 3.9, 4.1, 1.5, 2.5, model::Role::Opaque, -1);  // lintel, facing down
  const auto end = static_cast<std::uint32_t>(m.b.polygons.size());
  name_groups(m, {"shell", "door 1"});
  put_in_group(m, frame, end, 1);
  const model::Vec3 in_door{4.0, 2.0, 1.0};
  for (const bool named : {false, true}) {
    VisibilityConfig config = test_config(PvsMethod::Combined, true);
    if (named) config.frame_groups = {1};
    const VisibilityResult vis =
        compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config, group_names(m));
    EXPECT_EQ(vis.structure_items, named ? end : frame) << "named " << named;
    const Box& passage = vis.partition.cells[locate(vis.partition.nodes, in_door)];
    if (named) {
      EXPECT_GE(passage.min.y, 1.5 - 1e-9);
      EXPECT_LE(passage.max.y, 2.5 + 1e-9);
      EXPECT_LE(passage.max.z, 2.0 + 1e-9);
    } else {
      EXPECT_GT(passage.max.y - passage.min.y, 3.0) << "the passage holds the whole core";
    }
    std::vector<std::uint32_t> all(vis.partition.cells.size());
    std::iota(all.begin(), all.end(), 0u);
    EXPECT_EQ(testing::missed_pixels(m, vis, all, true), 0u) << "named " << named;
  }
}

TEST(StructureDetail, GlassIsStructureEvenInASmallGroup) {
  MiniBuilding m;
  m.rect(0, 0.0, 0, 1.2, 0.9, 2.1, model::Role::Glass);  // a window pane, its own 1.2 m group
  name_groups(m, {"window"});
  const auto polys = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  VisibilityConfig config;
  EXPECT_EQ(structure_polygons(polys, m.b.polygons, group_names(m), config)[0], 1);
  config.detail_groups = std::regex("window");  // unless the scene says so
  EXPECT_EQ(structure_polygons(polys, m.b.polygons, group_names(m), config)[0], 0);
}

TEST(StructureDetail, ClustersAreSmallInTrianglesAndSizeAndCoverEveryPolygonOnce) {
  MiniBuilding m;
  // A 6 m handrail of 600 small quads (1,200 triangles): one detail group, much longer than a cluster.
  for (int i = 0; i < 600; ++i) m.rect(1, 0.0, 0.9, 1.0, i * 0.01, (i + 1) * 0.01);
  name_groups(m, {"handrail"});
  auto polys = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  const std::vector<char> structure(polys.size(), 0);
  const VisItems items = make_vis_items(std::move(polys), m.b.polygons, structure);
  EXPECT_EQ(items.structure, 0u);
  EXPECT_GE(items.items.size(), 5u);
  std::set<std::uint32_t> covered;
  for (std::size_t i = 0; i < items.items.size(); ++i) {
    const VisPolygon& k = items.items[i];
    EXPECT_TRUE(k.detail);
    EXPECT_FALSE(k.opaque) << "detail hides nothing";
    EXPECT_LE(k.triangles.size(), kClusterTriangles);
    const model::Vec3 s = k.box.size();
    EXPECT_LE(std::max({s.x, s.y, s.z}), kClusterExtent + 1e-9);
    for (const auto p : items.polygons[i])
      EXPECT_TRUE(covered.insert(p).second) << "polygon " << p << " twice";
  }
  EXPECT_EQ(covered.size(), 600u);
}

TEST(StructureDetail, BoxMeetsRegionDegenerateCases) {
  const Box unit{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(box_meets_region(unit, {})) << "no planes: everything is in the region";
  // Wholly behind one plane (x >= 2).
  EXPECT_FALSE(box_meets_region(unit, {axial_plane(0, 2.0, 1.0)}));
  // Touching it: the plane x >= 1 meets the box's face; on the plane counts as in front (conservative).
  EXPECT_TRUE(box_meets_region(unit, {axial_plane(0, 1.0, 1.0)}));
  // A slab 0.4 <= x <= 0.6 crossing the box with no corner inside it.
  EXPECT_TRUE(box_meets_region(unit, {axial_plane(0, 0.4, 1.0), axial_plane(0, 0.6, -1.0)}));
  // Each plane has a corner in front, but no point of the box is in front of both (x >= 0.8 and
  // x + y <= 0.5 meet only outside it).
  const double r = 1.0 / std::sqrt(2.0);
  const Plane diagonal{{-r, -r, 0.0}, 0.5 * r};  // -(x + y) + 0.5 >= 0
  EXPECT_FALSE(box_meets_region(unit, {axial_plane(0, 0.8, 1.0), diagonal}));
  // A flat box (a detail polygon lying in z = 0) and a degenerate point box.
  EXPECT_TRUE(box_meets_region(Box{{0, 0, 0}, {1, 1, 0}}, {axial_plane(0, 0.5, 1.0)}));
  EXPECT_FALSE(box_meets_region(Box{{0.2, 0.2, 0.2}, {0.2, 0.2, 0.2}}, {axial_plane(1, 0.5, 1.0)}));
}

// The box a detail cluster stands as in the cells stage's ray caster: twelve triangles facing out, covering
// the surface once; a flat box is one face (two triangles) facing +axis; a point box has no area.
TEST(StructureDetail, BoxShellFacesOutAndCoversTheSurfaceOnce) {
  auto area = [](const std::array<model::Vec3, 3>& t) {
    return 0.5 * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
  };
  const Box box{{1, 2, 3}, {2, 4, 6}};
  const auto shell = box_shell(box);
  ASSERT_EQ(shell.size(), 12u);
  const model::Vec3 centre = 0.5 * (box.min + box.max);
  double total = 0.0;
  for (const auto& t : shell) {
    const model::Vec3 normal = glm::cross(t[1] - t[0], t[2] - t[0]);
    EXPECT_GT(glm::dot(normal, (t[0] + t[1] + t[2]) / 3.0 - centre), 0.0) << "faces out";
    for (const auto& p : t) EXPECT_TRUE(box.contains(p));
    total += area(t);
  }
  EXPECT_NEAR(total, 2.0 * (1 * 2 + 2 * 3 + 1 * 3), 1e-12);
  const auto flat = box_shell(Box{{0, 0, 1}, {2, 3, 1}});
  ASSERT_EQ(flat.size(), 10u) << "its one face, and the sides along x and y, which have no area";
  double flat_area = 0.0;
  for (const auto& t : flat) {
    flat_area += area(t);
    if (area(t) > 0.0) {
      EXPECT_GT(glm::cross(t[1] - t[0], t[2] - t[0]).z, 0.0) << "faces +z";
    }
  }
  EXPECT_NEAR(flat_area, 6.0, 1e-12);
  double point_area = 0.0;
  for (const auto& t : box_shell(Box{{1, 1, 1}, {1, 1, 1}})) point_area += area(t);
  EXPECT_EQ(point_area, 0.0);
}

// A closed box building of two rooms (door between), walls facing in; `hole` opens 1x1 m in the x = 8 wall.
MiniBuilding closed_house(bool hole, bool glazed) {
  MiniBuilding m = two_rooms_with_a_door();
  // two_rooms_with_a_door's x = 8 wall is polygon 3: replace it by one with a window hole.
  m.b.polygons[3].index_count = 0;
  if (hole) {
    m.rect_with_hole(0, 8.0, 0, 4, 0, 3, 1.5, 2.5, 1.0, 2.0);
    if (glazed) m.rect(0, 8.0, 1.5, 2.5, 1.0, 2.0, model::Role::Glass, -1);
  } else {
    m.rect(0, 8.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  }
  return m;
}

TEST(InsideFlood, AClosedBuildingReportsNoLeakAndOneHoleReportsItsPath) {
  VisibilityConfig config = test_config(PvsMethod::Conservative, true);
  config.seeds = {{1.0, 2.0, 1.5}};
  for (const auto& [hole, glazed] :
       {std::pair{false, false}, std::pair{true, true}, std::pair{true, false}}) {
    const MiniBuilding m = closed_house(hole, glazed);
    const VisibilityResult vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
    ASSERT_TRUE(vis.seeded);
    if (!hole || glazed) {
      EXPECT_TRUE(vis.leaks.empty()) << "hole " << hole << " glazed " << glazed;
      continue;
    }
    ASSERT_EQ(vis.leaks.size(), 1u);
    const LeakPath& leak = vis.leaks[0];
    EXPECT_NEAR(leak.area, 1.0, 1e-6);
    ASSERT_GE(leak.points.size(), 3u) << "seed, the door, the hole";
    EXPECT_EQ(leak.points.front(), config.seeds[0]);
    EXPECT_NEAR(leak.points.back().x, 8.0, 1e-9);
    EXPECT_NEAR(leak.points.back().y, 2.0, 1e-9);
    EXPECT_NEAR(leak.points.back().z, 1.5, 1e-9);
    bool through_door = false;
    for (const auto& p : leak.points) through_door |= std::abs(p.x - 4.0) < 1e-9;
    EXPECT_TRUE(through_door) << "the path goes from the seed's room through the door";
  }
  // Without seeds every cell is inside and the boundary's open parts are listed as before.
  config.seeds.clear();
  const MiniBuilding m = closed_house(true, false);
  const VisibilityResult vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  EXPECT_FALSE(vis.seeded);
  EXPECT_EQ(std::count(vis.inside.begin(), vis.inside.end(), 0), 0);
  EXPECT_FALSE(vis.leaks.empty());
}

TEST(InsideFlood, ARoomReachedOnlyThroughGlassIsOffTheWalkYetSeen) {
  // Room A (x 0..4) and room B (x 4..8) divided by a wall with a 2x1.5 m window; the seed is in A only.
  MiniBuilding m;
  m.rect(2, 0.0, 0, 8, 0, 4);
  m.rect(2, 3.0, 0, 8, 0, 4, model::Role::Opaque, -1);
  m.rect(0, 0.0, 0, 4, 0, 3);
  const auto far_wall = m.rect(0, 8.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  m.rect(1, 0.0, 0, 3, 0, 8);
  m.rect(1, 4.0, 0, 3, 0, 8, model::Role::Opaque, -1);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.0, 3.0, 0.5, 2.0);
  m.rect(0, 4.0, 1.0, 3.0, 0.5, 2.0, model::Role::Glass);
  VisibilityConfig config = test_config(PvsMethod::Combined, false);
  config.seeds = {{1.0, 2.0, 1.5}};
  const VisibilityResult vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  ASSERT_EQ(vis.partition.cells.size(), 2u);
  const std::uint32_t a = locate(vis.partition.nodes, {1, 2, 1.5}), b = 1 - a;
  EXPECT_TRUE(vis.inside[a]);
  EXPECT_FALSE(vis.inside[b]) << "no seed and no open way into B";
  EXPECT_TRUE(vis.polygon_pvs(b).empty()) << "off the walk: the renderer draws everything there";
  EXPECT_TRUE(has(vis.polygon_pvs(a), far_wall)) << "B's far wall is seen through the glass";
  EXPECT_TRUE(vis.leaks.empty());
}

// Two closed rooms whose windows face the same outside, with a solid block (two boxes: no single wall of it
// hides one window from the other) between them: no straight line from one window to the other misses
// the block, so neither room sees into the other, and the outside cells the flow passes are off the walk.
TEST(InsideFlood, ASightLineOutOfAWindowDoesNotPassThroughABlockToAnother) {
  MiniBuilding m;
  // Room A, [0,4] x [0,4], window in its east wall.
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 1.5, 2.5, 1.0, 2.0);
  m.rect(0, 4.0, 1.5, 2.5, 1.0, 2.0, model::Role::Glass);
  m.rect(1, 0.0, 0, 3, 0, 4);
  const auto a_north = m.rect(1, 4.0, 0, 3, 0, 4);
  m.rect(2, 0.0, 0, 4, 0, 4);
  m.rect(2, 3.0, 0, 4, 0, 4);
  // The block, [4.5,10] x [0.5,5.5], as two boxes: no single wall of it hides one window from the other.
  m.room({4.5, 0.5, 0.0}, {10.0, 2.8, 3.0});
  m.room({4.5, 2.8, 0.0}, {10.0, 5.5, 3.0});
  // Room B, [6,10] x [6,10], window in its south wall.
  m.rect(0, 6.0, 6, 10, 0, 3);
  m.rect(0, 10.0, 6, 10, 0, 3);
  m.rect_with_hole(1, 6.0, 0, 3, 6, 10, 1.0, 2.0, 7.0, 9.0);
  m.rect(1, 6.0, 1.0, 2.0, 7.0, 9.0, model::Role::Glass);
  const auto b_north = m.rect(1, 10.0, 0, 3, 6, 10);
  m.rect(2, 0.0, 6, 10, 6, 10);
  m.rect(2, 3.0, 6, 10, 6, 10);
  VisibilityConfig config = test_config(PvsMethod::Combined);
  config.seeds = {{2.0, 2.0, 1.5}, {8.0, 8.0, 1.5}};
  config.proof_pairs = 0;  // the flow alone
  const VisibilityResult vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  const std::uint32_t a = locate(vis.partition.nodes, {2, 2, 1.5}),
                      b = locate(vis.partition.nodes, {8, 8, 1.5});
  ASSERT_NE(a, b);
  EXPECT_TRUE(vis.inside[a] && vis.inside[b]);
  EXPECT_TRUE(vis.leaks.empty());
  EXPECT_FALSE(has(vis.polygon_pvs(a), b_north)) << "room B's far wall from room A";
  EXPECT_FALSE(has(vis.polygon_pvs(b), a_north)) << "room A's north wall from room B";
  EXPECT_EQ(testing::missed_pixels(m, vis, {a, b}), 0u);
}

}  // namespace test_structure_detail
}  // namespace walk::compiler
