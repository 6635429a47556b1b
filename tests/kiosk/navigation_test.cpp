#include "firmware-host/navigation.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "test_bundle.hpp"

namespace walk::kiosk {
namespace navigation_test {  // named, not anonymous: the suite compiles as unity batches

constexpr double kPi = std::numbers::pi;

class NavigationTest : public ::testing::Test {
 protected:
  NavigationTest() : contents_(testing::two_room_contents()), nav_(geometry()) {}
  NavGeometry geometry() const { return {contents_.vertices, contents_.indices, contents_.polygons}; }
  std::uint32_t group() const { return contents_.polygons[nav_.floor_polygon()].group; }
  // Walks in 1/30 s frames like the daemon does.
  void walk(double speed, double heading, double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 30.0 + 0.5); ++i) nav_.walk(speed, heading, 1.0 / 30.0);
  }
  bool free() const { return nav_.penetration(glm::dvec2(nav_.feet()), nav_.feet().z) == 0.0; }

  model::BundleContents contents_;
  Navigator nav_;
};

TEST_F(NavigationTest, PlacesOnTheFloorBelow) {
  ASSERT_TRUE(nav_.place({2, 2, 1.0}));
  EXPECT_DOUBLE_EQ(nav_.feet().z, 0.0);
  EXPECT_EQ(group(), 0u);
  EXPECT_FALSE(nav_.place({20, 2, 0}));   // outside the building: no floor
  EXPECT_FALSE(nav_.place({0.1, 2, 0}));  // body overlaps the glass wall
}

TEST_F(NavigationTest, GlassWallStopsTheWalker) {
  ASSERT_TRUE(nav_.place({2, 2, 0}));
  walk(1.0, kPi, 4.0);
  EXPECT_NEAR(nav_.feet().x, kBodyRadius, 1e-3);
  EXPECT_NEAR(nav_.feet().y, 2.0, 1e-9);
  EXPECT_TRUE(free());
  EXPECT_NEAR(nav_.distance_walked(), 2.0 - kBodyRadius, 1e-3);
}

TEST_F(NavigationTest, SlidesAlongAWall) {
  ASSERT_TRUE(nav_.place({1.0, 1.0, 0}));
  walk(1.0, -kPi / 4, 3.0);  // down-right, into the wall y = 0
  EXPECT_NEAR(nav_.feet().y, kBodyRadius, 1e-3);
  EXPECT_GT(nav_.feet().x, 2.9);  // kept moving along the wall
  EXPECT_LT(nav_.feet().x, 3.2);
  EXPECT_TRUE(free());
}

TEST_F(NavigationTest, WalksThroughTheDoorAndStepsUpTheSill) {
  ASSERT_TRUE(nav_.place({2, 2, 0}));
  walk(1.0, 0.0, 4.0);
  EXPECT_NEAR(nav_.feet().x, 6.0, 1e-3);
  EXPECT_NEAR(nav_.feet().z, 0.29, 1e-6);
  EXPECT_EQ(group(), 1u);
  EXPECT_TRUE(free());
}

TEST_F(NavigationTest, DoorJambStopsAWalkerAimedBesideTheDoor) {
  ASSERT_TRUE(nav_.place({2, 0.8, 0}));  // body spans y 0.55..1.05, the door starts at 1.5
  walk(1.0, 0.0, 4.0);
  EXPECT_NEAR(nav_.feet().x, 4.0 - kBodyRadius, 1e-3);
  EXPECT_DOUBLE_EQ(nav_.feet().z, 0.0);
  EXPECT_EQ(group(), 0u);
}

TEST_F(NavigationTest, SlightlyOffCentreWalkerSlidesThroughTheDoor) {
  ASSERT_TRUE(nav_.place({2, 1.6, 0}));  // body edge overlaps the jamb at y 1.5 by 0.15: it slides round
  walk(1.0, 0.0, 4.0);
  EXPECT_GT(nav_.feet().x, 5.0);
  EXPECT_EQ(group(), 1u);
  EXPECT_TRUE(free());
}

TEST_F(NavigationTest, DoesNotStepOntoAHalfMetrePlatform) {
  ASSERT_TRUE(nav_.place({1.5, 2.0, 0}));
  walk(1.0, kPi / 2, 3.0);
  EXPECT_NEAR(nav_.feet().y, 3.0 - kBodyRadius, 1e-3);
  EXPECT_DOUBLE_EQ(nav_.feet().z, 0.0);
}

TEST_F(NavigationTest, StepsDownBackIntoTheLowerRoom) {
  ASSERT_TRUE(nav_.place({6, 2, 0.29}));
  EXPECT_NEAR(nav_.feet().z, 0.29, 1e-6);
  walk(1.0, kPi, 4.0);
  EXPECT_NEAR(nav_.feet().x, 2.0, 1e-3);
  EXPECT_DOUBLE_EQ(nav_.feet().z, 0.0);
  EXPECT_EQ(group(), 0u);
}

TEST_F(NavigationTest, ReturnToStart) {
  ASSERT_TRUE(nav_.place({2, 2, 0}));
  walk(1.0, 0.0, 4.0);
  nav_.return_to_start();
  EXPECT_EQ(nav_.feet(), glm::dvec3(2, 2, 0));
  EXPECT_EQ(group(), 0u);
}

TEST_F(NavigationTest, LongMovesCannotTunnelThroughWalls) {
  ASSERT_TRUE(nav_.place({2, 1, 0}));
  nav_.move({5.0, 0.0});  // one huge step at the partition: substeps stop it
  EXPECT_NEAR(nav_.feet().x, 4.0 - kBodyRadius, 1e-3);
}

TEST_F(NavigationTest, OpeningPolygonsNeverBlock) {
  // Without the lintel/sill the walker would pass anyway; this pins that the Opening face is skipped.
  ASSERT_TRUE(nav_.place({3.5, 2, 0}));
  EXPECT_EQ(nav_.penetration({4.0, 2.0}, 0.0), 0.0);
  EXPECT_GT(nav_.penetration({4.0, 1.0}, 0.0), 0.2);
}

}  // namespace navigation_test
}  // namespace walk::kiosk
