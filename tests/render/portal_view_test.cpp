// Portal culling's geometry (render/portal_view.hpp), pure CPU: projections clipped at the eye, three cells
// in a row whose doors line up only from some places, an eye standing in a doorway, a door behind the eye,
// one-way portals, and the cells a box touches when it lies in a splitting plane.
#include "render/portal_view.hpp"

#include <gtest/gtest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <vector>

namespace walk::render {
namespace portal_view_test {  // named, not anonymous: the suite compiles as unity batches

// Looking along +x from `eye`, 90 degrees each way, square image: a point (x, y, z) ahead shows at
// ndc ((y - eye.y) / (x - eye.x) * -1, (z - eye.z) / (x - eye.x)) (+y is to the left).
glm::mat4 looking_along_x(const glm::vec3& eye, float sign = 1.0f) {
  const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(sign, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  return glm::perspective(glm::radians(90.0f), 1.0f, 0.05f, 500.0f) * view;
}

model::PortalRecord portal(int axis, float coord, float u0, float u1, float v0, float v1, std::uint32_t back,
                           std::uint32_t front,
                           std::uint32_t ways = model::kPortalForward | model::kPortalBackward) {
  model::PortalRecord p{};
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  p.bounds_min[axis] = p.bounds_max[axis] = coord;
  p.bounds_min[u] = u0;
  p.bounds_max[u] = u1;
  p.bounds_min[v] = v0;
  p.bounds_max[v] = v1;
  p.back = back;
  p.front = front;
  p.flags = std::uint32_t(axis) | ways;
  return p;
}

Box box(float x0, float y0, float z0, float x1, float y1, float z1) {
  return Box{{x0, y0, z0}, {x1, y1, z1}};
}

// Cells 0 | 1 | 2 along x, split at x = 4 and x = 8 (cell 0: x < 4). The door from 0 to 1 spans y 1..2, the
// door from 1 to 2 spans y 3.5..4.5; both z 0..2. Units: one box in each cell, away from the doors.
// From (2, 1.5) the first door spans y / x slopes -0.25..0.25, the second 0.33..0.5: out of line.
struct ThreeCells {
  std::vector<model::NodeRecord> nodes{
      {{1.0, 0.0, 0.0, -4.0}, 1, -1},   // x >= 4: node 1, else cell 0
      {{1.0, 0.0, 0.0, -8.0}, -3, -2},  // x >= 8: cell 2, else cell 1
  };
  std::vector<model::PortalRecord> portals{portal(0, 4.0f, 1.0f, 2.0f, 0.0f, 2.0f, 0, 1),
                                           portal(0, 8.0f, 3.5f, 4.5f, 0.0f, 2.0f, 1, 2)};
  std::vector<Box> units{box(2.5f, 1.0f, 0.0f, 3.5f, 2.0f, 1.0f), box(6.0f, 3.0f, 0.0f, 7.0f, 3.5f, 1.0f),
                         box(10.0f, 3.5f, 0.0f, 11.0f, 5.0f, 1.0f)};
};

TEST(PortalProjection, QuadAheadMapsToItsCornersRectangle) {
  const glm::vec3 eye(0.0f, 0.0f, 0.0f);
  const glm::vec3 quad[4] = {
      {2.0f, -1.0f, -1.0f}, {2.0f, 1.0f, -1.0f}, {2.0f, 1.0f, 0.5f}, {2.0f, -1.0f, 0.5f}};
  const NdcRect r = project_polygon(quad, looking_along_x(eye));
  EXPECT_NEAR(r.lo[0], -0.5f, 1e-3f);
  EXPECT_NEAR(r.hi[0], 0.5f, 1e-3f);
  EXPECT_NEAR(r.lo[1], -0.5f, 1e-3f);
  EXPECT_NEAR(r.hi[1], 0.25f, 1e-3f);
}

TEST(PortalProjection, QuadBehindIsEmptyAndQuadAcrossTheEyeReachesTheEdge) {
  const glm::mat4 m = looking_along_x(glm::vec3(0.0f));
  const glm::vec3 behind[4] = {
      {-2.0f, -1.0f, -1.0f}, {-2.0f, 1.0f, -1.0f}, {-2.0f, 1.0f, 1.0f}, {-2.0f, -1.0f, 1.0f}};
  EXPECT_TRUE(project_polygon(behind, m).empty());
  // A floor strip from behind the eye to ahead of it, left of the view axis: clipped at the eye, its image
  // runs off the bottom of the screen and past its left edge, so it must cover the lower left corner.
  const glm::vec3 across[4] = {
      {-1.0f, 0.1f, -1.0f}, {3.0f, 0.1f, -1.0f}, {3.0f, 1.0f, -1.0f}, {-1.0f, 1.0f, -1.0f}};
  const NdcRect r = project_polygon(across, m);
  ASSERT_FALSE(r.empty());
  EXPECT_LE(r.lo[1], -1.0f);
  EXPECT_LE(r.lo[0], -1.0f);
}

TEST(PortalProjection, BoxesBehindAreEmptyAndBoxesRoundTheEyeFillTheScreen) {
  const glm::mat4 m = looking_along_x(glm::vec3(0.0f));
  EXPECT_TRUE(project_box(box(-3.0f, -1.0f, -1.0f, -2.0f, 1.0f, 1.0f), m).empty());
  const NdcRect round = project_box(box(-1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f), m);
  EXPECT_TRUE(round.meets(whole_screen()));
  EXPECT_LE(round.lo[0], -1.0f);
  EXPECT_GE(round.hi[1], 1.0f);
  EXPECT_TRUE(project_box(empty_box(), m).empty());
}

TEST(PortalView, DoorsThatDoNotLineUpHideTheFarCell) {
  ThreeCells s;
  PortalView view(s.portals, s.nodes, 3, s.units);
  const glm::vec3 eye(2.0f, 1.5f, 1.0f);
  view.look(0, eye, looking_along_x(eye));
  EXPECT_EQ(view.cells_reached(), 2u);
  EXPECT_TRUE(view.shows(0));
  EXPECT_FALSE(view.shows(1)) << "the unit in cell 1 (slopes 0.3..0.5) lies beside what the door shows";
  EXPECT_FALSE(view.shows(2)) << "door 1-2 is out of line with door 0-1 from here";
  // From further right the second door shows through the first: cell 2 and its unit come into view.
  const glm::vec3 aside(2.0f, 0.5f, 1.0f);
  view.look(0, aside, looking_along_x(aside));
  EXPECT_EQ(view.cells_reached(), 3u);
  EXPECT_TRUE(view.shows(2));
}

TEST(PortalView, AnEyeInTheDoorwaySeesTheNextCellWhole) {
  ThreeCells s;
  PortalView view(s.portals, s.nodes, 3, s.units);
  // On the door's plane, the door is seen edge on; every direction into cell 1 passes it.
  const glm::vec3 eye(4.0f, 1.5f, 1.0f);
  view.look(0, eye, looking_along_x(eye));
  EXPECT_TRUE(view.shows(1));
  EXPECT_TRUE(view.shows(2)) << "door 1-2 is in plain view from the doorway";
}

TEST(PortalView, ADoorBehindTheEyeLeadsNowhere) {
  ThreeCells s;
  PortalView view(s.portals, s.nodes, 3, s.units);
  const glm::vec3 eye(6.0f, 2.5f, 1.0f);
  view.look(1, eye, looking_along_x(eye));
  EXPECT_FALSE(view.shows(0)) << "door 0-1 is behind the eye";
  EXPECT_TRUE(view.shows(2));
  // Turned round, door 0-1 is ahead and door 1-2 behind.
  view.look(1, eye, looking_along_x(eye, -1.0f));
  EXPECT_TRUE(view.shows(0));
  EXPECT_FALSE(view.shows(2));
}

TEST(PortalView, OneWayPortalsPassOneWay) {
  ThreeCells s;
  s.portals[0].flags = 0 | model::kPortalForward;  // sight passes from cell 0 into cell 1 only
  PortalView view(s.portals, s.nodes, 3, s.units);
  const glm::vec3 eye(6.0f, 1.5f, 1.0f);
  view.look(1, eye, looking_along_x(eye, -1.0f));
  EXPECT_EQ(view.cells_reached(), 1u);
  EXPECT_FALSE(view.shows(0));
  const glm::vec3 back(2.0f, 1.5f, 1.0f);
  view.look(0, back, looking_along_x(back));
  EXPECT_EQ(view.cells_reached(), 2u);
}

TEST(PortalView, BoxesInASplittingPlaneTouchBothCells) {
  ThreeCells s;
  s.units = {box(4.0f, 0.0f, 0.0f, 4.0f, 3.0f, 2.0f),  // a wall in the plane x = 4
             box(3.0f, 0.0f, 0.0f, 9.0f, 1.0f, 1.0f),  // a bench through all three cells
             box(4.0005f, 0.0f, 0.0f, 5.0f, 1.0f, 1.0f), empty_box()};
  const PortalView view(s.portals, s.nodes, 3, s.units);
  EXPECT_EQ(view.unit_cells(0).size(), 2u);
  EXPECT_EQ(view.unit_cells(1).size(), 3u);
  EXPECT_EQ(view.unit_cells(2).size(), 2u) << "within the slack of the plane: both sides, conservatively";
  EXPECT_EQ(view.unit_cells(3).size(), 0u);
}

TEST(PortalView, SightStartsInEveryCellTheNearPlaneReaches) {
  ThreeCells s;
  // Near plane 5 cm: an eye 1 cm from the wall at x = 4 has its near rectangle in cell 1 already.
  const glm::vec3 close(3.99f, 1.5f, 1.0f), far(3.0f, 1.5f, 1.0f);
  EXPECT_EQ(near_cells(s.nodes, 3, 0, close, looking_along_x(close)), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(near_cells(s.nodes, 3, 0, far, looking_along_x(far)), (std::vector<std::uint32_t>{0}));
  // Turned away from the wall, the near rectangle stays in cell 0.
  EXPECT_EQ(near_cells(s.nodes, 3, 0, close, looking_along_x(close, -1.0f)), (std::vector<std::uint32_t>{0}));
  // The walk starts in both: cell 1 is seen through the whole screen, not only through the door.
  PortalView view(s.portals, s.nodes, 3, s.units);
  view.look(0, close, looking_along_x(close));
  EXPECT_EQ(view.start_cells().size(), 2u);
  const NdcRect whole = view.seen_through(1);
  EXPECT_LE(whole.lo[0], -1.0f);
  EXPECT_GE(whole.hi[1], 1.0f);
}

TEST(PortalView, AnEyeOutsideEveryCellSeesEverything) {
  ThreeCells s;
  PortalView view(s.portals, s.nodes, 3, s.units);
  const glm::vec3 eye(2.0f, 1.5f, 1.0f);
  view.look(7, eye, looking_along_x(eye));
  EXPECT_TRUE(view.sees_everything());
  for (std::uint32_t u = 0; u < 3; ++u) EXPECT_TRUE(view.shows(u));
}

}  // namespace portal_view_test
}  // namespace walk::render
