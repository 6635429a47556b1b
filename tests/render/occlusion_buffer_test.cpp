// The occlusion buffer hides a box only where its occluders cover every point of the box's image nearer
// than the box: its degenerate cases (a hole, a seam between two polygons, a polygon seen edge on, one cut by
// the near plane or past the far plane, a box just behind a wall, one off the screen) each keep the box.
// Pure CPU.
#include "render/occlusion_buffer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

namespace walk::render::test {
namespace occlusion_buffer_test {  // named, not anonymous: the suite compiles as unity batches

constexpr int kColumns = 64;

// Eye at the origin looking along +x, z up, 90 degrees vertical field of view, 16:9.
glm::mat4 looking_along_x() {
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 16.0f / 9.0f, 0.05f, 500.0f);
  return projection * glm::lookAt(glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
}

// A rectangle in the plane x = `x`, y in [y0, y1], z in [z0, z1], wound to face the eye at the origin.
struct Rectangle {
  std::array<glm::vec3, 4> corners;
  std::array<std::uint32_t, 6> triangles{0, 2, 1, 0, 3, 2};
  std::vector<OccluderEdge> edges{{0, 1, true}, {1, 2, true}, {2, 3, true}, {3, 0, true}};
};
Rectangle rectangle(float x, float y0, float y1, float z0, float z1) {
  return {{glm::vec3(x, y0, z0), glm::vec3(x, y1, z0), glm::vec3(x, y1, z1), glm::vec3(x, y0, z1)}};
}

void add(OcclusionBuffer& buffer, const Rectangle& r) {
  buffer.add(r.corners, r.triangles, r.edges);
}

OcclusionBuffer with_one(const Rectangle& r) {
  OcclusionBuffer buffer;
  buffer.clear(looking_along_x(), 1280, 720, kColumns);
  buffer.begin_group();
  add(buffer, r);
  buffer.end_group();
  buffer.finish();
  return buffer;
}

Box box(glm::vec3 lo, glm::vec3 hi) {
  return {{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}};
}

TEST(OcclusionBuffer, AWallHidesWhatIsBehindItOnly) {
  const OcclusionBuffer buffer = with_one(rectangle(5.0f, -20.0f, 20.0f, -20.0f, 20.0f));
  EXPECT_EQ(buffer.covered_pixels(), std::size_t(buffer.columns() * buffer.rows()));
  EXPECT_TRUE(buffer.hides(box({8, -1, -1}, {9, 1, 1})));
  EXPECT_FALSE(buffer.hides(box({3, -1, -1}, {4, 1, 1}))) << "in front of the wall";
  EXPECT_FALSE(buffer.hides(box({4, -1, -1}, {6, 1, 1}))) << "through the wall";
  EXPECT_FALSE(buffer.hides(box({5.00001f, -1, -1}, {6, 1, 1})))
      << "a hair behind the wall: within the depth buffer's resolution";
  EXPECT_FALSE(buffer.hides(box({-1, -1, -1}, {9, 1, 1}))) << "reaching round the eye";
  EXPECT_FALSE(buffer.hides(box({8, 1, 1}, {9, -1, -1}))) << "empty";
  EXPECT_FALSE(buffer.hides(box({-9, -1, -1}, {-8, 1, 1}))) << "behind the eye: the frustum's call";
}

TEST(OcclusionBuffer, AHoleAndTheWallsEdgeLetSightThrough) {
  // A wall with a door: three rectangles round the opening y in [-0.5, 0.5], z in [-1, 1], one surface.
  OcclusionBuffer buffer;
  buffer.clear(looking_along_x(), 1280, 720, kColumns);
  buffer.begin_group();
  std::vector<Rectangle> parts{
      rectangle(5.0f, -20.0f, -0.5f, -20.0f, 20.0f), rectangle(5.0f, 0.5f, 20.0f, -20.0f, 20.0f),
      rectangle(5.0f, -0.5f, 0.5f, 1.0f, 20.0f), rectangle(5.0f, -0.5f, 0.5f, -20.0f, -1.0f)};
  // Their shared edges are closed (the left and right parts meet the lintel and sill along x = 5).
  for (auto& part : parts) add(buffer, part);
  buffer.end_group();
  buffer.finish();
  EXPECT_FALSE(buffer.hides(box({10, -0.1f, -0.1f}, {11, 0.1f, 0.1f}))) << "seen through the door";
  EXPECT_TRUE(buffer.hides(box({10, 3, 3}, {11, 4, 4}))) << "behind the solid wall";
  EXPECT_FALSE(buffer.hides(box({10, 0.3f, 0.3f}, {11, 1.5f, 1.5f}))) << "partly through the door";
}

TEST(OcclusionBuffer, ASeamIsClosedOnlyWhenBothSidesAreOneSurface) {
  // Two halves of a wall meeting at y = 0, a box right behind the seam.
  Rectangle left = rectangle(5.0f, -20.0f, 0.0f, -20.0f, 20.0f),
            right = rectangle(5.0f, 0.0f, 20.0f, -20.0f, 20.0f);
  const Box behind_seam = box({8, -0.5f, -0.5f}, {9, 0.5f, 0.5f});
  {
    // Each half its own group, every edge open: no pixel on the seam is covered by one of them whole.
    OcclusionBuffer buffer;
    buffer.clear(looking_along_x(), 1280, 720, kColumns);
    for (const auto* half : {&left, &right}) {
      buffer.begin_group();
      add(buffer, *half);
      buffer.end_group();
    }
    buffer.finish();
    EXPECT_FALSE(buffer.hides(behind_seam));
    EXPECT_TRUE(buffer.hides(box({8, 2, 2}, {9, 3, 3})));
  }
  {
    // One group, the shared edge (left's 1-2, right's 3-0) closed.
    left.edges[1].open = false;
    right.edges[3].open = false;
    OcclusionBuffer buffer;
    buffer.clear(looking_along_x(), 1280, 720, kColumns);
    buffer.begin_group();
    add(buffer, left);
    add(buffer, right);
    buffer.end_group();
    buffer.finish();
    EXPECT_TRUE(buffer.hides(behind_seam));
    EXPECT_EQ(buffer.covered_pixels(), std::size_t(buffer.columns() * buffer.rows()));
  }
}

TEST(OcclusionBuffer, AGroupCoversAPixelOnlyWhereItsOwnOpenEdgesDoNot) {
  // A near wall covering the screen, and a far panel behind it whose open edges cross the screen: the far
  // panel's edges must not take back what the near wall covers whole.
  OcclusionBuffer buffer;
  buffer.clear(looking_along_x(), 1280, 720, kColumns);
  for (const Rectangle& r :
       {rectangle(5.0f, -20.0f, 20.0f, -20.0f, 20.0f), rectangle(7.0f, -1.0f, 1.0f, -1.0f, 1.0f)}) {
    buffer.begin_group();
    add(buffer, r);
    buffer.end_group();
  }
  buffer.finish();
  EXPECT_EQ(buffer.covered_pixels(), std::size_t(buffer.columns() * buffer.rows()));
  EXPECT_TRUE(buffer.hides(box({8, 0.8f, 0.8f}, {9, 1.2f, 1.2f})));
}

TEST(OcclusionBuffer, AWallSeenEdgeOnCoversNothing) {
  // The plane y = 0 through the eye: a wall seen exactly edge on.
  Rectangle r;
  r.corners = {glm::vec3(1, 0, -20), glm::vec3(40, 0, -20), glm::vec3(40, 0, 20), glm::vec3(1, 0, 20)};
  const OcclusionBuffer buffer = with_one(r);
  EXPECT_EQ(buffer.covered_pixels(), 0u);
  EXPECT_FALSE(buffer.hides(box({50, -0.01f, -1}, {51, 0.01f, 1})));
}

TEST(OcclusionBuffer, TheNearPlaneCutsAWallItCrosses) {
  // A wall 2 cm beside the eye, from behind it to far ahead: the near plane (5 cm) cuts it on the screen,
  // and what lies beyond the cut part is drawn, so the cut is an open edge.
  Rectangle r;
  r.corners = {glm::vec3(-1, 0.02f, -20), glm::vec3(30, 0.02f, -20), glm::vec3(30, 0.02f, 20),
               glm::vec3(-1, 0.02f, 20)};
  const OcclusionBuffer buffer = with_one(r);
  EXPECT_GT(buffer.covered_pixels(), 0u);
  EXPECT_LT(buffer.covered_pixels(), std::size_t(buffer.columns() * buffer.rows()));
  // Beyond the wall, seen through its part past the near plane: hidden.
  EXPECT_TRUE(buffer.hides(box({10, 2.0f, -0.1f}, {11, 2.2f, 0.1f})));
  // Beyond the wall, seen where the near plane cut it away: drawn.
  EXPECT_FALSE(buffer.hides(box({1, 0.85f, -0.1f}, {1.1f, 0.95f, 0.1f})));
}

TEST(OcclusionBuffer, AWallPastTheFarPlaneHidesNothing) {
  const OcclusionBuffer buffer = with_one(rectangle(600.0f, -2000.0f, 2000.0f, -2000.0f, 2000.0f));
  EXPECT_EQ(buffer.covered_pixels(), 0u);
  EXPECT_FALSE(buffer.hides(box({700, -1, -1}, {701, 1, 1})));
}

}  // namespace occlusion_buffer_test
}  // namespace walk::render::test
