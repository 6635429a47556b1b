// Automatic exposure's percentile by area: refinement's crowd of vertices next to a lamp must not move it.
#include <gtest/gtest.h>

#include <vector>

#include "compiler/lighting/auto_exposure.hpp"

namespace walk::compiler {
namespace test_auto_exposure {  // named, not anonymous: the suite compiles as unity batches

TEST(AutoExposure, PercentileFollowsAreaNotVertexCount) {
  // One large dim wall (value 1, area 9) and, next to a lamp, 90 refined vertices (value 50, area 0.001
  // each).
  std::vector<double> values{1.0}, weights{9.0};
  for (int i = 0; i < 90; ++i) {
    values.push_back(50.0);
    weights.push_back(0.001);
  }
  // 99 % of the area is dim: the 95th percentile is the wall's light, though 99 % of the vertices are bright.
  EXPECT_EQ(weighted_percentile(values, weights, 0.95), 1.0);
  EXPECT_EQ(weighted_percentile(values, weights, 0.995), 50.0);
  // Equal weights: the plain percentile (the smallest value with at least that share at or below it).
  const std::vector<double> v{4, 1, 3, 2}, w{1, 1, 1, 1};
  EXPECT_EQ(weighted_percentile(v, w, 0.5), 2.0);
  EXPECT_EQ(weighted_percentile(v, w, 0.51), 3.0);
  EXPECT_EQ(weighted_percentile(v, w, 0.0), 1.0);
  EXPECT_EQ(weighted_percentile(v, w, 1.0), 4.0);
  EXPECT_EQ(weighted_percentile(v, w, 7.0), 4.0) << "a share past 1 is 1";
}

TEST(AutoExposure, NothingWeighedGivesZeroAndZeroWeightsAreSkipped) {
  EXPECT_EQ(weighted_percentile({}, {}, 0.95), 0.0);
  const std::vector<double> v{5, 7}, none{0, -1};
  EXPECT_EQ(weighted_percentile(v, none, 0.95), 0.0);
  const std::vector<double> one{0, 2};
  EXPECT_EQ(weighted_percentile(v, one, 0.0), 7.0) << "a value of no area is never the answer";
  // Unequal lengths: the pairs that exist.
  const std::vector<double> three{1, 2, 3}, two{1, 1};
  EXPECT_EQ(weighted_percentile(three, two, 1.0), 2.0);
}

}  // namespace test_auto_exposure
}  // namespace walk::compiler
