// Barycentric weights as light is read at a point: exact inside, clamped outside, thirds when degenerate.
#include <gtest/gtest.h>

#include "compiler/geometry/triangle_weights.hpp"

namespace walk::compiler {
namespace test_triangle_weights {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Weights are sums of products of coordinates near 1: a few ulps.
constexpr double kWeightTolerance = 1e-12;

void expect_weights(const std::array<double, 3>& w, double a, double b, double c) {
  EXPECT_NEAR(w[0], a, kWeightTolerance);
  EXPECT_NEAR(w[1], b, kWeightTolerance);
  EXPECT_NEAR(w[2], c, kWeightTolerance);
  EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, kWeightTolerance);
}

TEST(TriangleWeights, CornersCentroidAndEdgeMidpoint) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  expect_weights(triangle_weights(a, b, c, a), 1, 0, 0);
  expect_weights(triangle_weights(a, b, c, c), 0, 0, 1);
  expect_weights(triangle_weights(a, b, c, (a + b + c) / 3.0), 1.0 / 3, 1.0 / 3, 1.0 / 3);
  expect_weights(triangle_weights(a, b, c, Vec3(1, 1, 0)), 0, 0.5, 0.5);
}

TEST(TriangleWeights, PointOffThePlaneReadsItsProjection) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  expect_weights(triangle_weights(a, b, c, Vec3(0.5, 0.5, 0.3)), 0.5, 0.25, 0.25);
}

TEST(TriangleWeights, PointOutsideIsClampedOntoTheTriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  const auto w = triangle_weights(a, b, c, Vec3(3, -1, 0));  // beyond corner b
  for (const double x : w) EXPECT_GE(x, 0.0);
  expect_weights(w, 0, 1, 0);
  const auto u = triangle_weights(a, b, c, Vec3(1, -1e-9, 0));  // a hair below edge a-b
  expect_weights(u, 0.5, 0.5, 0);
}

TEST(TriangleWeights, DegenerateTrianglesGiveThirds) {
  const Vec3 a(1, 1, 1);
  expect_weights(triangle_weights(a, a, a, a), 1.0 / 3, 1.0 / 3, 1.0 / 3);              // one point
  expect_weights(triangle_weights(a, a, Vec3(2, 1, 1), a), 1.0 / 3, 1.0 / 3, 1.0 / 3);  // repeated corner
  expect_weights(triangle_weights(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3), Vec3(2, 2, 2)), 1.0 / 3,
                 1.0 / 3, 1.0 / 3);  // collinear
}

}  // namespace test_triangle_weights
}  // namespace walk::compiler
