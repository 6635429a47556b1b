// The voxel flood that confirms leaks: the triangle-box predicate on its degenerate cases, a closed room, a
// hole, a slit, and a slanted roof over axial cells, where the cell flood alone reports openings that the
// roof closes.
#include <gtest/gtest.h>

#include <algorithm>

#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/voxel_flood.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_voxel_flood {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
using testing::MiniBuilding;
using testing::test_config;

using Triangle = std::array<Vec3, 3>;
const Vec3 kCentre{0.0}, kHalf{0.5};  // the unit box round the origin

TEST(TriangleMeetsBox, CrossingTouchingAndMissing) {
  EXPECT_TRUE(triangle_meets_box({{{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}}}, kCentre, kHalf)) << "through it";
  EXPECT_FALSE(triangle_meets_box({{{2, 2, 2}, {3, 2, 2}, {2, 3, 2}}}, kCentre, kHalf)) << "far off";
  // In the plane of a face, and at a corner only: touching is meeting.
  EXPECT_TRUE(triangle_meets_box({{{-1, -1, 0.5}, {1, -1, 0.5}, {0, 1, 0.5}}}, kCentre, kHalf));
  EXPECT_TRUE(triangle_meets_box({{{0.5, 0.5, 0.5}, {2, 0.5, 0.5}, {0.5, 2, 0.5}}}, kCentre, kHalf));
  EXPECT_FALSE(
      triangle_meets_box({{{-1, -1, 0.5 + 1e-9}, {1, -1, 0.5 + 1e-9}, {0, 1, 0.5 + 1e-9}}}, kCentre, kHalf))
      << "just above the top face";
  // Its box overlaps the box, the triangle passes by the corner: only an edge-by-axis cross separates.
  EXPECT_FALSE(triangle_meets_box({{{1.3, -0.1, 0}, {-0.1, 1.3, 0}, {2, 2, 0}}}, kCentre, kHalf));
  EXPECT_TRUE(triangle_meets_box({{{0.9, -0.1, 0}, {-0.1, 0.9, 0}, {2, 2, 0}}}, kCentre, kHalf));
  // Slanted through the box's middle; its plane passing beside it.
  EXPECT_TRUE(triangle_meets_box({{{-3, -3, -3}, {3, -3, 3}, {0, 3, 0}}}, kCentre, kHalf));
  EXPECT_FALSE(triangle_meets_box({{{-3, -3, -1.9}, {3, -3, 4.1}, {0, 3, 1.1}}}, kCentre, kHalf));
  // A huge triangle round the box, in a plane through it.
  EXPECT_TRUE(triangle_meets_box({{{-1e3, -1e3, 0.1}, {1e3, -1e3, 0.1}, {0, 1e3, 0.1}}}, kCentre, kHalf));
}

TEST(TriangleMeetsBox, DegenerateTriangles) {
  EXPECT_TRUE(triangle_meets_box({{{0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}}}, kCentre, kHalf))
      << "a point inside";
  EXPECT_FALSE(triangle_meets_box({{{0.6, 0.1, 0.1}, {0.6, 0.1, 0.1}, {0.6, 0.1, 0.1}}}, kCentre, kHalf))
      << "a point outside";
  EXPECT_TRUE(triangle_meets_box({{{-2, 0, 0}, {0, 0, 0}, {2, 0, 0}}}, kCentre, kHalf))
      << "a segment through";
  EXPECT_FALSE(triangle_meets_box({{{0.3, 1.3, 0}, {0.8, 0.8, 0}, {1.3, 0.3, 0}}}, kCentre, kHalf))
      << "a segment passing the corner";
  EXPECT_TRUE(triangle_meets_box({{{0, 1, 0}, {0.5, 0.5, 0}, {1, 0, 0}}}, kCentre, kHalf))
      << "a segment touching the edge";
}

// A closed 4 x 4 x 3 m room, walls facing in, with optional openings in the x = 4 wall (a y, z window).
MiniBuilding room(double hole_y0 = 0.0, double hole_y1 = 0.0, double hole_z0 = 0.0, double hole_z1 = 0.0) {
  MiniBuilding m;
  m.rect(2, 0.0, 0, 4, 0, 4);
  m.rect(2, 3.0, 0, 4, 0, 4, model::Role::Opaque, -1);
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect(1, 0.0, 0, 3, 0, 4);
  m.rect(1, 4.0, 0, 3, 0, 4, model::Role::Opaque, -1);
  if (hole_y1 > hole_y0)
    m.rect_with_hole(0, 4.0, 0, 4, 0, 3, hole_y0, hole_y1, hole_z0, hole_z1, -1);
  else
    m.rect(0, 4.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  return m;
}

VoxelFlood flood(const MiniBuilding& m, std::vector<Vec3> seeds) {
  const VisibilityResult vis =
      compute_visibility(m.b.vertices, m.b.indices, m.b.polygons, test_config(PvsMethod::Conservative, true));
  return flood_voxels(vis.polygons, vis.structure_items, vis.partition.bounds, seeds);
}

Box face_of(const Box& bounds, int axis, bool max_side) {
  Box f = bounds;
  f.min[axis] = f.max[axis] = max_side ? bounds.max[axis] : bounds.min[axis];
  return f;
}

int faces_reached(const VoxelFlood& f, const Box& bounds) {
  int n = 0;
  for (int a = 0; a < 3; ++a)
    for (const bool side : {false, true}) n += f.reaches_beyond(face_of(bounds, a, side), a, side);
  return n;
}

TEST(VoxelFlood, AClosedRoomKeepsItAndAHoleLetsItOutOnItsSideOnly) {
  const Box bounds{{0, 0, 0}, {4, 4, 3}};
  const VoxelFlood closed = flood(room(), {{2, 2, 1.5}});
  EXPECT_GT(std::count(closed.reached.begin(), closed.reached.end(), 1), 1000);
  EXPECT_EQ(faces_reached(closed, bounds), 0);
  const VoxelFlood holed = flood(room(1.5, 2.5, 1.0, 2.0), {{2, 2, 1.5}});
  EXPECT_TRUE(holed.reaches_beyond(face_of(bounds, 0, true), 0, true));
  EXPECT_EQ(faces_reached(holed, bounds), 1) << "the outside layer is not passed round to the other faces";
  Box beside = face_of(bounds, 0, true);
  beside.max.y = 1.0;  // the wall's x = 4 face away from the hole
  EXPECT_FALSE(holed.reaches_beyond(beside, 0, true));
  // A slit under a voxel wide is closed wherever it lies.
  for (const double at : {1.0, 1.01, 1.07})
    EXPECT_EQ(faces_reached(flood(room(at, at + 0.9 * kFloodVoxel, 0.5, 2.5), {{2, 2, 1.5}}), bounds), 0)
        << at;
  // A seed in a wall's voxels starts nothing.
  const VoxelFlood on_wall = flood(room(1.5, 2.5, 1.0, 2.0), {{4.0, 2.0, 0.5}});
  EXPECT_EQ(std::count(on_wall.reached.begin(), on_wall.reached.end(), 1), 0);
}

// A room under a gable roof (ridge along y at x = 2, eaves at z = 3, ridge at z = 5), gable ends closed by
// triangles. The cells are boxes to z = 5, so the cell flood meets the boundary above the eaves; the roof
// closes it. With a 1 x 1 m hole in one slope the flood leaks, with its path.
MiniBuilding gabled_room(bool hole) {
  MiniBuilding m;
  m.rect(2, 0.0, 0, 4, 0, 4);
  m.rect(0, 0.0, 0, 4, 0, 3);
  m.rect(0, 4.0, 0, 4, 0, 3, model::Role::Opaque, -1);
  m.rect(1, 0.0, 0, 3, 0, 4);
  m.rect(1, 4.0, 0, 3, 0, 4, model::Role::Opaque, -1);
  // Gable ends (quads with two corners the same: one triangle and one of no area), facing in.
  m.quad({4, 0, 3}, {0, 0, 3}, {2, 0, 5}, {2, 0, 5});
  m.quad({0, 4, 3}, {4, 4, 3}, {2, 4, 5}, {2, 4, 5});
  // Slopes facing in: the x < 2 slope z = 3 + x, the other z = 7 - x.
  auto slope_left = [&](double x0, double x1, double y0, double y1) {
    m.quad({x0, y1, 3 + x0}, {x1, y1, 3 + x1}, {x1, y0, 3 + x1}, {x0, y0, 3 + x0});
  };
  if (hole) {
    slope_left(0.0, 0.6, 0.0, 4.0);
    slope_left(1.4, 2.0, 0.0, 4.0);
    slope_left(0.6, 1.4, 0.0, 1.5);
    slope_left(0.6, 1.4, 2.5, 4.0);
  } else {
    slope_left(0.0, 2.0, 0.0, 4.0);
  }
  m.quad({2, 4, 5}, {4, 4, 3}, {4, 0, 3}, {2, 0, 5});
  return m;
}

TEST(VoxelFlood, ASlantedRoofClosesWhatTheCellsLeaveOpen) {
  VisibilityConfig config = test_config(PvsMethod::Conservative, true);
  config.seeds = {{2.0, 2.0, 1.5}, {2.0, 2.0, 4.2}};  // the room and the roof space
  const MiniBuilding closed = gabled_room(false);
  const VisibilityResult vis =
      compute_visibility(closed.b.vertices, closed.b.indices, closed.b.polygons, config);
  ASSERT_TRUE(vis.seeded);
  EXPECT_TRUE(vis.leaks.empty());
  EXPECT_GT(vis.leaks_unconfirmed, 0u) << "the cells alone reach the boundary above the eaves";
  EXPECT_NE(vis.summary().find("the voxel flood did not"), std::string::npos);
  const MiniBuilding holed = gabled_room(true);
  const VisibilityResult leaky =
      compute_visibility(holed.b.vertices, holed.b.indices, holed.b.polygons, config);
  ASSERT_FALSE(leaky.leaks.empty());
  EXPECT_EQ(leaky.leaks.front().points.front(), config.seeds[0]);
}

}  // namespace test_voxel_flood
}  // namespace walk::compiler
