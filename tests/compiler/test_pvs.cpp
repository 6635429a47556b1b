// PVS hard cases, each judged against ray-cast polygon-ID cube images from viewpoints in every cell.
#include <gtest/gtest.h>

#include <algorithm>

#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/verify_visibility.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_pvs {  // named, not anonymous: the suite compiles as unity batches

using testing::all_cells;
using testing::MiniBuilding;
using testing::missed_pixels;
using testing::small_judge;
using testing::test_config;

struct Judged {
  VisibilityResult vis;
  std::uint64_t missed = 0;
  std::vector<std::vector<std::uint32_t>> exact;
};

Judged judge(const MiniBuilding& m, PvsMethod method, bool cull_back_faces = false) {
  Judged j;
  j.vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, test_config(method, cull_back_faces));
  const VisibilityJudge judge(m.b.vertices, m.b.indices, m.b.polygons, small_judge(cull_back_faces));
  for (std::uint32_t c = 0; c < j.vis.partition.cells.size(); ++c) {
    const CellViews v =
        judge.views(j.vis.partition.cells[c], c, portal_viewpoints(j.vis.graph, j.vis.partition.cells[c], c));
    j.missed += judge.missed(v, j.vis.polygon_pvs(c));
    j.exact.push_back(v.exact);
  }
  return j;
}

bool has(const std::vector<std::uint32_t>& v, std::uint32_t x) {
  return std::binary_search(v.begin(), v.end(), x);
}

// Rooms (4x4x3) along x, walls between them at x = 4, 8, ...; `doors[i]` puts a 1x2 door in wall i.
MiniBuilding row_of_rooms(std::vector<bool> doors, std::vector<std::uint32_t>* far_wall = nullptr) {
  MiniBuilding m;
  const double len = 4.0 * double(doors.size() + 1);
  const auto end = m.row_shell(len);
  if (far_wall) far_wall->push_back(end);
  for (std::size_t i = 0; i < doors.size(); ++i) {
    const double x = 4.0 * double(i + 1);
    if (doors[i])
      m.rect_with_hole(0, x, 0, 4, 0, 3, 1.5, 2.5, 0.0, 2.0);
    else
      m.rect(0, x, 0, 4, 0, 3);
  }
  return m;
}

TEST(Pvs, DoorInAThinWallConservativeMissesNothing) {
  MiniBuilding m = row_of_rooms({true});
  // A box in the far room, only partly visible through the door.
  m.room({6.0, 1.0, 0.0}, {6.5, 1.5, 0.5});
  for (const auto method : {PvsMethod::Conservative, PvsMethod::Combined}) {
    const Judged j = judge(m, method);
    EXPECT_EQ(j.vis.partition.cells.size(), 2u) << pvs_method_name(method);
    EXPECT_EQ(j.missed, 0u) << pvs_method_name(method);
    for (std::size_t c = 0; c < j.exact.size(); ++c)
      for (const auto p : j.exact[c])
        EXPECT_TRUE(has(j.vis.polygon_pvs(c), p)) << "cell " << c << " polygon " << p;
  }
}

TEST(Pvs, SealedCellSeesNothingBeyondItsWalls) {
  std::vector<std::uint32_t> far;
  const MiniBuilding m = row_of_rooms({false}, &far);
  const Judged j = judge(m, PvsMethod::Conservative);
  ASSERT_EQ(j.vis.partition.cells.size(), 2u);
  EXPECT_TRUE(j.vis.graph.portals.empty());
  EXPECT_EQ(j.missed, 0u);
  // The far end wall (x = 8) is in the second cell only.
  const std::uint32_t first = locate(j.vis.partition.nodes, {1, 1, 1});
  EXPECT_FALSE(has(j.vis.polygon_pvs(first), far[0]));
  EXPECT_TRUE(has(j.vis.polygon_pvs(1 - first), far[0]));
}

TEST(Pvs, SeparatingPlanesCullWhatNoDoorSequenceShows) {
  // Four rooms in a row; doors in walls 1 and 3 are at opposite ends of the wall, wall 2's door in the
  // middle: the last room is reached by the flow but its polygons outside the sight lines are culled.
  MiniBuilding m;
  const double len = 16.0;
  m.rect(2, 0.0, 0, len, 0, 4);
  m.rect(2, 3.0, 0, len, 0, 4);
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect(0, len, 0, 4, 0, 3);
  m.rect(1, 0.0, 0, 3, 0, len);
  m.rect(1, 4.0, 0, 3, 0, len);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 0.0, 0.8, 0.0, 2.0);
  m.rect_with_hole(0, 8.0, 0, 4, 0, 3, 1.6, 2.4, 0.0, 2.0);
  m.rect_with_hole(0, 12.0, 0, 4, 0, 3, 3.2, 4.0, 0.0, 2.0);
  const Judged cons = judge(m, PvsMethod::Combined);
  const Judged cells = judge(m, PvsMethod::Conservative);
  EXPECT_EQ(cons.missed, 0u);
  EXPECT_EQ(cells.missed, 0u);
  std::size_t cons_total = 0, cells_total = 0;
  for (std::size_t c = 0; c < cons.vis.pvs.size(); ++c) cons_total += cons.vis.polygon_pvs(c).size();
  for (std::size_t c = 0; c < cells.vis.pvs.size(); ++c) cells_total += cells.vis.polygon_pvs(c).size();
  EXPECT_LE(cons_total, cells_total);
}

// A flow that runs past its step budget takes every cell its portals might see, whole: still conservative
// (nothing seen is missed, the full flow's PVS is inside it), and a sealed room stays sealed.
TEST(Pvs, FlowPastItsBudgetTakesWhatItsPortalsMightSee) {
  for (const bool sealed : {false, true}) {
    std::vector<std::uint32_t> far;
    MiniBuilding m = row_of_rooms({!sealed, true, true}, &far);
    m.room({13.0, 1.0, 0.0}, {13.5, 1.5, 0.5});  // a box in the last room
    VisibilityConfig config = test_config(PvsMethod::Conservative);
    const VisibilityResult full = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
    config.flow_budget = 1;
    const VisibilityResult cut = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
    ASSERT_EQ(cut.partition.cells.size(), 4u);
    EXPECT_EQ(full.flow_fallbacks, 0u);
    // The budget is per portal: of the directed portals (0-1 unless sealed, 1-2, 2-3) those whose flow
    // goes on past the room beyond them run past it; a flow into a room with no other door takes one step.
    EXPECT_EQ(cut.flow_fallbacks, sealed ? 2u : 4u);
    for (std::uint32_t c = 0; c < 4; ++c)
      for (const auto p : full.polygon_pvs(c))
        EXPECT_TRUE(has(cut.polygon_pvs(c), p)) << "cell " << c << " polygon " << p;
    EXPECT_EQ(missed_pixels(m, cut, {0, 1, 2, 3}), 0u);
    const std::uint32_t first = locate(cut.partition.nodes, {1, 1, 1});
    EXPECT_EQ(has(cut.polygon_pvs(first), far[0]), !sealed) << "the far end wall from the first room";
  }
}

// Past its budget a flow finds the cells by a flow over cells alone and tests the items of each by portal
// pairs: still conservative, and a box in a reached room that no line through both doors meets stays out
// (taking every cell the portals might see, whole, put it in). The far room has two doors: the flow over
// items goes through both (the box in it is never seen, so the room is never done), the flow over cells
// only through the first (the room is reached), so the one runs past a budget of two steps and the other
// ends within it.
TEST(Pvs, FlowPastItsBudgetTestsItemsByPortalPairs) {
  MiniBuilding m;
  m.row_shell(12.0);
  m.rect_with_hole(0, 4.0, 0, 4, 0, 3, 0.2, 1.0, 0.0, 2.0);  // doors at opposite ends of their walls
  m.rect_with_hole(0, 8.0, 0, 3, 0, 3, 2.0, 2.6, 0.0, 2.0);
  m.rect_with_hole(0, 8.0, 3, 4, 0, 3, 3.0, 3.8, 0.0, 2.0);
  const auto first_box = static_cast<std::uint32_t>(m.b.polygons.size());
  m.room({11.0, 0.1, 0.0}, {11.5, 0.5, 0.5});  // in the far room's corner, behind the second door's wall
  VisibilityConfig config = test_config(PvsMethod::Combined);
  config.proof_pairs = 0;  // the flow alone
  const VisibilityResult full = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  config.flow_budget = 2;
  const VisibilityResult cut = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  ASSERT_EQ(cut.partition.cells.size(), 3u);
  EXPECT_EQ(full.flow_fallbacks, 0u);
  EXPECT_GT(cut.flow_fallbacks, 0u);
  EXPECT_EQ(cut.flow_cell_fallbacks, 0u);
  const std::uint32_t first = locate(cut.partition.nodes, {1, 1, 1}),
                      last = locate(cut.partition.nodes, {11, 2, 1});
  EXPECT_TRUE(has(cut.flow_cells[first], last)) << "the far room is reached through both doors";
  EXPECT_EQ(missed_pixels(m, cut, {0, 1, 2}), 0u);
  for (std::uint32_t c = 0; c < 3; ++c)
    for (const auto p : full.polygon_pvs(c))
      EXPECT_TRUE(has(cut.polygon_pvs(c), p)) << "cell " << c << " polygon " << p;
  for (std::uint32_t p = first_box; p < first_box + 6; ++p) {
    EXPECT_FALSE(has(full.polygon_pvs(first), p)) << "box polygon " << p;
    EXPECT_FALSE(has(cut.polygon_pvs(first), p)) << "box polygon " << p;
  }
}

TEST(Pvs, SourceNarrowsToWhatSeesThroughEachDoor) {
  // Rooms along x, 10 m wide and 3 m high: A [0, 1], B [1, 2], C [2, 3], D [3, 4], E [4, 10]; doors 2 m
  // high at x = 1 (y 0.5..9.5), x = 2 (y 4..6), x = 3 (y 8..9.5), x = 4 (y 0.5..9.5). In plan a sight line
  // through the doors at x = 2 and 3 leaves A's door at y <= 4, and from there crosses x = 4 at y >= 10:
  // nothing in E is seen from A. Through the whole of A's door (a source never narrowed) the flow would
  // reach E and keep its far wall.
  MiniBuilding m;
  const double xs[] = {0.0, 1.0, 2.0, 3.0, 4.0, 10.0};
  for (int r = 0; r < 5; ++r) {
    m.rect(2, 0.0, xs[r], xs[r + 1], 0, 10);
    m.rect(2, 3.0, xs[r], xs[r + 1], 0, 10);
    m.rect(1, 0.0, 0, 3, xs[r], xs[r + 1]);
    m.rect(1, 10.0, 0, 3, xs[r], xs[r + 1]);
  }
  m.rect(0, 0.0, 0, 10, 0, 3);
  const auto far_wall = m.rect(0, 10.0, 0, 10, 0, 3);
  m.rect_with_hole(0, 1.0, 0, 10, 0, 3, 0.5, 9.5, 0.0, 2.0);
  m.rect_with_hole(0, 2.0, 0, 10, 0, 3, 4.0, 6.0, 0.0, 2.0);
  m.rect_with_hole(0, 3.0, 0, 10, 0, 3, 8.0, 9.5, 0.0, 2.0);
  m.rect_with_hole(0, 4.0, 0, 10, 0, 3, 0.5, 9.5, 0.0, 2.0);
  for (const auto method : {PvsMethod::Conservative, PvsMethod::Combined}) {
    const Judged j = judge(m, method);
    EXPECT_EQ(j.missed, 0u) << pvs_method_name(method);
    const std::uint32_t a = locate(j.vis.partition.nodes, {0.5, 5.0, 1.0});
    const std::uint32_t e = locate(j.vis.partition.nodes, {9.0, 5.0, 1.0});
    EXPECT_FALSE(has(j.vis.polygon_pvs(a), far_wall)) << pvs_method_name(method);
    EXPECT_TRUE(has(j.vis.polygon_pvs(e), far_wall));
    for (std::size_t c = 0; c < j.exact.size(); ++c)
      for (const auto p : j.exact[c])
        EXPECT_TRUE(has(j.vis.polygon_pvs(c), p)) << "cell " << c << " polygon " << p;
  }
}

TEST(Pvs, AWallInsideACellHidesWhatLiesBehindIt) {
  // Two rooms and a door (x = 4, y 1.5..2.5); in the far room a slanted wall, which no axial cell face
  // follows, stands between the door and a small box: the box lies in the wall's umbra seen from the door.
  MiniBuilding m = row_of_rooms({true});
  const model::Vec3 a(5.0, 0.2, 0.0), b(5.4, 3.8, 0.0), c(5.4, 3.8, 2.95), d(5.0, 0.2, 2.95);
  m.quad(a, d, c, b);  // facing the door (-x)
  m.quad(a, b, c, d);  // and its back, facing the box
  const auto first_box = static_cast<std::uint32_t>(m.b.polygons.size());
  m.room({6.9, 1.9, 0.2}, {7.1, 2.1, 0.4});
  const auto end_box = static_cast<std::uint32_t>(m.b.polygons.size());
  // The single-occluder test inside the flow settles it, and so does the hidden-polygon proof on its own;
  // with neither, the flow keeps the box.
  struct Setting {
    bool occluders;
    int proof_pairs;
  };
  for (const auto [occluders, proof_pairs] : {Setting{true, 0}, Setting{false, 0}, Setting{false, 256}}) {
    VisibilityConfig config = test_config(PvsMethod::Combined, true);
    config.occluders = occluders;
    config.proof_pairs = proof_pairs;
    config.detail_area = 0.0;  // the box is structure here: the proof tries structure only
    const VisibilityResult vis = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
    EXPECT_EQ(missed_pixels(m, vis, all_cells(vis), true), 0u)
        << "occluders " << occluders << " proofs " << proof_pairs;
    const std::uint32_t near_room = locate(vis.partition.nodes, {1, 2, 1});
    std::size_t box_faces = 0;
    for (std::uint32_t p = first_box; p < end_box; ++p)
      box_faces += has(vis.polygon_pvs(near_room), p) ? 1 : 0;
    if (occluders) {
      EXPECT_EQ(box_faces, 0u) << "the box behind the wall, from the room with the door";
      EXPECT_GT(vis.flow_occluded, 0u);
    } else if (proof_pairs > 0) {
      EXPECT_EQ(box_faces, 0u) << "the proof alone hides the box";
      EXPECT_GT(vis.proofs.hidden, 0u);
    } else {
      EXPECT_GT(box_faces, 0u) << "without occluders or proofs the flow keeps it";
    }
  }
}

TEST(Pvs, ProofsOverTheirBudgetShrinkEachAllowanceAndStayConservative) {
  // The scene above, its proofs alone hiding the box; then a budget of pairs far below what they ask for.
  MiniBuilding m = row_of_rooms({true});
  const model::Vec3 a(5.0, 0.2, 0.0), b(5.4, 3.8, 0.0), c(5.4, 3.8, 2.95), d(5.0, 0.2, 2.95);
  m.quad(a, d, c, b);
  m.quad(a, b, c, d);
  m.room({6.9, 1.9, 0.2}, {7.1, 2.1, 0.4});
  VisibilityConfig config = test_config(PvsMethod::Combined, true);
  config.occluders = false;
  config.proof_pairs = 256;
  config.detail_area = 0.0;
  const VisibilityResult full = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  ASSERT_GT(full.proofs.hidden, 0u);
  EXPECT_EQ(full.proof_pairs_capped, 0);
  config.proof_pair_budget = 0.01 * full.proof_pairs_wanted;
  const VisibilityResult capped = compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, config);
  EXPECT_EQ(capped.proof_pairs_wanted, full.proof_pairs_wanted);
  EXPECT_EQ(capped.proof_pairs_capped, std::max(1, int(256 * 0.01)));
  EXPECT_LE(double(capped.proofs.pairs), config.proof_pair_budget + double(capped.proofs.tried))
      << "each item stops at its allowance (one pair over, the one that finds it spent)";
  EXPECT_LT(capped.proofs.pairs, full.proofs.pairs);
  EXPECT_NE(capped.summary().find("capped at"), std::string::npos) << capped.summary();
  for (std::uint32_t cell = 0; cell < capped.partition.cells.size(); ++cell) {
    const auto kept = capped.polygon_pvs(cell);
    for (const auto p : full.polygon_pvs(cell))
      EXPECT_TRUE(has(kept, p)) << "cell " << cell << " polygon " << p;
  }
  EXPECT_EQ(missed_pixels(m, capped, all_cells(capped), true), 0u);
}

TEST(Pvs, PortalsMeetingAtACellCorner) {
  // Four rooms around (4,4): each dividing wall has its opening against the middle, so the four
  // openings meet along the vertical line x = y = 4 and the diagonal rooms see each other across it.
  MiniBuilding m;
  m.rect(2, 0.0, 0, 8, 0, 8);
  m.rect(2, 3.0, 0, 8, 0, 8);
  m.rect(0, 0.0, 0, 8, 0, 3);
  m.rect(0, 8.0, 0, 8, 0, 3);
  m.rect(1, 0.0, 0, 3, 0, 8);
  m.rect(1, 8.0, 0, 3, 0, 8);
  m.rect(0, 4.0, 0, 3, 0, 3);  // x = 4 wall: open for y in 3..5
  m.rect(0, 4.0, 5, 8, 0, 3);
  m.rect(1, 4.0, 0, 3, 0, 3);  // y = 4 wall: open for x in 3..5 (u = z, v = x)
  m.rect(1, 4.0, 0, 3, 5, 8);
  const auto marker = m.rect(2, 0.01, 6.5, 7.5, 6.5, 7.5);  // a mat in the far corner of room (x>4, y>4)
  for (const auto method : {PvsMethod::Conservative, PvsMethod::Combined}) {
    const Judged j = judge(m, method);
    EXPECT_GE(j.vis.partition.cells.size(), 4u);
    EXPECT_EQ(j.missed, 0u) << pvs_method_name(method);
    const std::uint32_t a = locate(j.vis.partition.nodes, {1, 1, 1});
    EXPECT_TRUE(has(j.vis.polygon_pvs(a), marker)) << "the diagonal room is seen across the corner";
  }
}

TEST(Pvs, StackedStoreysWithAStairwell) {
  MiniBuilding m;
  m.rect(2, 0.0, 0, 6, 0, 6);
  // A 0.2 m slab between the storeys with a 2x1 m stairwell through it (x 1..3, y 1..2).
  m.rect_with_hole(2, 3.0, 0, 6, 0, 6, 1.0, 3.0, 1.0, 2.0);
  m.rect_with_hole(2, 3.2, 0, 6, 0, 6, 1.0, 3.0, 1.0, 2.0);
  m.rect(0, 1.0, 1.0, 2.0, 3.0, 3.2);  // stairwell sides (x planes: u = y, v = z)
  m.rect(0, 3.0, 1.0, 2.0, 3.0, 3.2);
  m.rect(1, 1.0, 3.0, 3.2, 1.0, 3.0);  // (y planes: u = z, v = x)
  m.rect(1, 2.0, 3.0, 3.2, 1.0, 3.0);
  m.rect(2, 6.0, 0, 6, 0, 6);  // roof
  m.rect(0, 0.0, 0, 6, 0, 6);  // x walls, both storeys (u = y, v = z)
  m.rect(0, 6.0, 0, 6, 0, 6);
  m.rect(1, 0.0, 0, 6, 0, 6);  // y walls (u = z, v = x)
  m.rect(1, 6.0, 0, 6, 0, 6);
  const auto upstairs = m.rect(0, 5.99, 1, 5, 4, 5);  // a picture on the upper storey's x = 6 wall
  const Judged j = judge(m, PvsMethod::Conservative);
  ASSERT_GE(j.vis.partition.cells.size(), 2u);
  bool vertical = false;
  for (const auto& p : j.vis.graph.portals) vertical |= p.axis == 2 && std::abs(p.area - 2.0) < 1e-6;
  EXPECT_TRUE(vertical) << "the stairwell is a horizontal portal of 2 m2";
  EXPECT_EQ(j.missed, 0u);
  const std::uint32_t down = locate(j.vis.partition.nodes, {3, 3, 1});
  EXPECT_TRUE(has(j.vis.polygon_pvs(down), upstairs));
}

TEST(Pvs, SampledNeverAddsWhatCannotBeSeen) {
  const MiniBuilding m = row_of_rooms({true, false});
  const Judged s = judge(m, PvsMethod::Sampled);
  const Judged c = judge(m, PvsMethod::Conservative);
  for (std::size_t cell = 0; cell < s.vis.pvs.size(); ++cell)
    for (const auto p : s.vis.polygon_pvs(cell)) EXPECT_TRUE(has(c.vis.polygon_pvs(cell), p));
}

// Two rooms along x (0..4, 4..8) with inward-facing outer walls, split at x = 4 by `divider`: the renderer
// culls back faces, and so do the PVS and the judge here.
MiniBuilding two_rooms_facing_in(int divider_facing_a, int divider_facing_b) {
  MiniBuilding m;
  m.room_inward({0, 0, 0}, {8, 4, 3});
  // The divider: a quad facing room A (-x) and/or one facing room B (+x), back to back.
  if (divider_facing_a) m.rect(0, 4.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  if (divider_facing_b) m.rect(0, 4.0, 0, 4, 0, 3, model::Role::Opaque, 1);
  return m;
}

TEST(Pvs, BackToBackWallsSealWhenBackFacesAreCulled) {
  const MiniBuilding m = two_rooms_facing_in(1, 1);
  for (const auto method : {PvsMethod::Conservative, PvsMethod::Combined}) {
    const Judged j = judge(m, method, true);
    ASSERT_EQ(j.vis.partition.cells.size(), 2u);
    EXPECT_TRUE(j.vis.graph.portals.empty()) << pvs_method_name(method);
    EXPECT_EQ(j.missed, 0u);
    // Room A's PVS: its own five inward faces and the divider's face towards it; not room B's, and not the
    // divider's back (turned away from all of room A).
    const std::uint32_t a = locate(j.vis.partition.nodes, {1, 1, 1});
    EXPECT_EQ(j.vis.polygon_pvs(a).size(), 6u) << pvs_method_name(method);
    EXPECT_FALSE(has(j.vis.polygon_pvs(a), 7u));  // the divider facing B
    EXPECT_TRUE(has(j.vis.polygon_pvs(a), 6u));   // the divider facing A
  }
}

TEST(Pvs, OneSidedWallIsAOneWayPortal) {
  // The divider faces room A only: from room B the renderer sees its back, culls it, and shows room A.
  const MiniBuilding m = two_rooms_facing_in(1, 0);
  for (const auto method : {PvsMethod::Conservative, PvsMethod::Combined}) {
    const Judged j = judge(m, method, true);
    ASSERT_EQ(j.vis.partition.cells.size(), 2u);
    ASSERT_EQ(j.vis.graph.portals.size(), 1u);
    const Portal& p = j.vis.graph.portals[0];
    EXPECT_FALSE(p.forward);  // from A (the -x side) sight lines meet the divider's front
    EXPECT_TRUE(p.backward);  // from B they pass its back
    EXPECT_EQ(j.missed, 0u) << pvs_method_name(method);
    const std::uint32_t a = locate(j.vis.partition.nodes, {1, 1, 1});
    const std::uint32_t b = locate(j.vis.partition.nodes, {6, 1, 1});
    EXPECT_FALSE(has(j.vis.polygon_pvs(a), 1u))
        << pvs_method_name(method);              // room B's far wall (x = 8), out of room A's sight
    EXPECT_TRUE(has(j.vis.polygon_pvs(b), 0u));  // room A's far wall (x = 0), seen from B through the divider
    for (std::size_t c = 0; c < j.exact.size(); ++c)
      for (const auto e : j.exact[c])
        EXPECT_TRUE(has(j.vis.polygon_pvs(c), e)) << "cell " << c << " polygon " << e;
  }
  // Drawn from both sides, the divider closes the face both ways: no portal.
  const Judged two_sided = judge(m, PvsMethod::Conservative, false);
  EXPECT_TRUE(two_sided.vis.graph.portals.empty());
}

TEST(Pvs, ComputeCellsFillsTheBundleSections) {
  MiniBuilding m = row_of_rooms({true, true});
  m.b.meta = {};
  const auto counts = compute_cells(m.b, test_config(PvsMethod::Combined));
  EXPECT_EQ(counts.cells_out, m.b.cells.size());
  EXPECT_GE(m.b.cells.size(), 3u);
  EXPECT_EQ(m.b.nodes.size() + 1, m.b.cells.size());
  std::size_t total = 0;
  for (const auto& c : m.b.cells) {
    EXPECT_EQ(c.pvs_first, total);
    total += c.pvs_count;
    for (std::uint32_t i = c.pvs_first + 1; i < c.pvs_first + c.pvs_count; ++i)
      EXPECT_LT(m.b.pvs[i - 1], m.b.pvs[i]);  // sorted, no repeats
  }
  EXPECT_EQ(total, m.b.pvs.size());
}

// `walk verify visibility`'s ratio in clusters: a polygon counts for the one cluster holding it; polygons
// in no cluster, ids past the model and records running past the list count nothing.
TEST(VerifyClusters, CountsTheClustersHoldingThePolygonsSeen) {
  // Clusters {0, 1}, {2}, {3, 4, 9 (past the model)}, and one whose range runs past the list; polygon 5 in
  // none.
  const std::vector<model::ClusterRecord> clusters{{{0, 0, 0}, {1, 1, 1}, 0, 2},
                                                   {{0, 0, 0}, {1, 1, 1}, 2, 1},
                                                   {{0, 0, 0}, {1, 1, 1}, 3, 3},
                                                   {{0, 0, 0}, {1, 1, 1}, 6, 5}};
  const std::vector<std::uint32_t> list{0, 1, 2, 3, 4, 9};
  const std::vector<std::uint32_t> of = cluster_of_polygons(6, clusters, list);
  EXPECT_EQ(of, (std::vector<std::uint32_t>{0, 0, 1, 2, 2, kNoCluster}));
  EXPECT_EQ(clusters_holding(std::vector<std::uint32_t>{}, of), 0u);
  EXPECT_EQ(clusters_holding(std::vector<std::uint32_t>{0, 1}, of), 1u);     // one chair, two polygons
  EXPECT_EQ(clusters_holding(std::vector<std::uint32_t>{1, 2, 4}, of), 3u);  // three clusters
  EXPECT_EQ(clusters_holding(std::vector<std::uint32_t>{5, 7, 1000}, of), 0u);
  EXPECT_TRUE(cluster_of_polygons(0, clusters, list).empty());

  // The report: sums over cells, the worst cell's ratio, and a cell with no exact cluster left out of the
  // worst (as a cell with no exact polygon is).
  VerifyReport r;
  r.rows = {{0, 40, 10, 0, 100, 4, 2}, {1, 30, 30, 0, 100, 6, 1}, {2, 5, 0, 0, 100, 3, 0}};
  summarise(r);
  EXPECT_DOUBLE_EQ(r.cluster_ratio, 13.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.cluster_ratio_worst, 6.0);
  EXPECT_DOUBLE_EQ(r.cluster_pvs_average, 13.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.cluster_exact_average, 1.0);
  EXPECT_DOUBLE_EQ(r.ratio, 75.0 / 40.0);  // the polygons' ratio as before
  VerifyReport none;
  none.rows = {{0, 40, 10, 0, 100, 0, 0}};
  summarise(none);
  EXPECT_EQ(none.cluster_ratio, 0.0);
  EXPECT_EQ(none.cluster_ratio_worst, 0.0);
}

}  // namespace test_pvs
}  // namespace walk::compiler
