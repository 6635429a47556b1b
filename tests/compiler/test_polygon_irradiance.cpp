// The exact projected solid angle of a polygon against the catalogue's closed form and numeric integration,
// its degenerate cases, and direct light next to a panel, where point samples alone are noisy.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

#include "compiler/lighting/direct_light.hpp"
#include "compiler/lighting/polygon_irradiance.hpp"

namespace walk::compiler {
namespace test_polygon_irradiance {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
constexpr double kPi = std::numbers::pi;

// Configuration factor from a point to a parallel a x b rectangle with a corner h straight above it
// (Howell's catalogue B-3); the projected solid angle is pi times it.
double corner_factor(double a, double b, double h) {
  const double x = a / h, y = b / h;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
}

// The integral of max(cos_r, 0) |cos_e| / r^2 over the parallelogram `origin` + s u + t v (s, t in [0, 1]),
// by the midpoint rule on n x n cells: shares nothing with Lambert's formula.
double integrated(const Vec3& origin, const Vec3& u, const Vec3& v, const Vec3& point, const Vec3& normal,
                  int n = 1000) {
  const Vec3 emitter = glm::normalize(glm::cross(u, v));
  const double cell = glm::length(glm::cross(u, v)) / (double(n) * n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 d = origin + u * ((i + 0.5) / n) + v * ((j + 0.5) / n) - point;
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      sum += std::max(glm::dot(normal, d) / r, 0.0) * std::abs(glm::dot(emitter, d) / r) / r2 * cell;
    }
  return sum;
}

std::vector<Vec3> parallelogram(const Vec3& origin, const Vec3& u, const Vec3& v) {
  return {origin, origin + u, origin + u + v, origin + v};
}

TEST(PolygonIrradiance, RectangleAboveACornerMatchesTheCatalogue) {
  // 2 m x 1 m, 1 m above a corner, and below its centre (four corner rectangles of 1 m x 0.5 m).
  const auto rect = parallelogram({0, 0, 1}, {2, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(projected_solid_angle(rect, {0, 0, 0}, {0, 0, 1}), kPi * corner_factor(2, 1, 1), 1e-12);
  EXPECT_NEAR(projected_solid_angle(rect, {1, 0.5, 0}, {0, 0, 1}), 4 * kPi * corner_factor(1, 0.5, 1), 1e-12);
  EXPECT_NEAR(corner_factor(2, 1, 1), 0.16737, 1e-5);  // the catalogue's tabulated value
}

TEST(PolygonIrradiance, EitherWindingAndAnyReceiverTiltAgreeWithIntegration) {
  const Vec3 origin{-0.3, 0.2, 0.5}, u{0.6, 0.0, 0.1}, v{0.0, 0.6, 0.0};
  const auto forward = parallelogram(origin, u, v);
  const std::vector<Vec3> backward(forward.rbegin(), forward.rend());
  // Facing it, tilted, and tilted so far that the receiver's tangent plane cuts the panel in two.
  for (const Vec3& normal : {Vec3{0, 0, 1}, glm::normalize(Vec3{1, 0, 1}), glm::normalize(Vec3{1, 0, 0.3})}) {
    const double expected = integrated(origin, u, v, {0, 0, 0}, normal);
    ASSERT_GT(expected, 0.0);
    // The midpoint rule's own error at 1,000 x 1,000 cells: about 1e-6 relative here.
    EXPECT_NEAR(projected_solid_angle(forward, {0, 0, 0}, normal), expected, 1e-5 * expected);
    EXPECT_NEAR(projected_solid_angle(backward, {0, 0, 0}, normal), expected, 1e-5 * expected);
  }
}

TEST(PolygonIrradiance, DegenerateCasesGiveNothingOrStayBounded) {
  const auto square = parallelogram({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  // Wholly behind the receiver's tangent plane, and seen edge-on from its own plane outside it.
  EXPECT_EQ(projected_solid_angle(square, {0, 0, 0}, {0, 0, -1}), 0.0);
  EXPECT_NEAR(projected_solid_angle(square, {3, 0, 1}, {0, 0, 1}), 0.0, 1e-15);  // angles cancel
  EXPECT_EQ(projected_solid_angle(square, {3, 0, 1}, {-1, 0, 0}), 0.0);
  // Lying in the tangent plane, the point at a corner; and touching the plane along an edge only.
  EXPECT_EQ(projected_solid_angle(parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), {0, 0, 0}, {0, 0, 1}), 0.0);
  EXPECT_EQ(projected_solid_angle(parallelogram({0, 0, 0}, {1, 0, 0}, {0, 0, -1}), {0, 0, 0}, {0, 0, 1}),
            0.0);
  // Fewer than three corners.
  EXPECT_EQ(projected_solid_angle(std::vector<Vec3>{{0, 0, 1}, {1, 0, 1}}, {0, 0, 0}, {0, 0, 1}), 0.0);
  // A nanometre below its centre the square fills the hemisphere: pi, never more.
  const double near_centre = projected_solid_angle(square, {0, 0, 1 - 1e-9}, {0, 0, 1});
  EXPECT_GT(near_centre, 0.999999 * kPi);
  EXPECT_LE(near_centre, kPi);
  // Right under a corner: a quarter of the hemisphere; at the corner itself the edges through the point
  // drop out and the rest stays finite.
  EXPECT_NEAR(projected_solid_angle(square, {-1, -1, 1 - 1e-9}, {0, 0, 1}), 0.25 * kPi, 1e-6);
  const double at_corner = projected_solid_angle(square, {-1, -1, 1}, {0, 0, 1});
  EXPECT_TRUE(std::isfinite(at_corner) && at_corner >= 0.0 && at_corner <= kPi);
}

TEST(PolygonIrradiance, SmallFarPolygonFollowsThePointSourceLaw) {
  // 1 cm square 10 m away, tilted 60 degrees from the receiver's normal: A cos cos / r^2 to 1e-6.
  const Vec3 centre = 10.0 * Vec3{std::sin(kPi / 3), 0, std::cos(kPi / 3)};
  const auto square = parallelogram(centre - Vec3{0, 0.005, 0.005}, {0, 0.01, 0}, {0, 0, 0.01});
  const double expected = 1e-4 * std::cos(kPi / 3) * std::sin(kPi / 3) / 100.0;  // emitter faces -x
  EXPECT_NEAR(projected_solid_angle(square, {0, 0, 0}, {0, 0, 1}), expected, 1e-6 * expected);
}

// Direct light 0.3 m below a corner of a 0.6 m panel, where jittered points on the panel are off by
// percents: with nothing in the way the panel's light is exact at any sample count.
TEST(DirectLight, UnshadowedPanelNextToTheReceiverIsExactAtFewSamples) {
  model::Luminaire l;
  l.position = {0.3, 0.3, 0.3};
  l.normal = {0, 0, -1};
  l.width = l.height = 0.6;
  l.power = {100, 50, 10};
  const SurfaceSample s{{0, 0, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
  const TriangleBvh empty({});
  // rho Phi F / A, from the shadow rays' origin 0.1 mm off the surface (direct_light's kShadowOffset).
  const double expected = 0.5 * 100.0 * corner_factor(0.6, 0.6, 0.3 - 1e-4) / (0.6 * 0.6);
  for (int samples : {1, 4, 8}) {
    const auto b = direct_light({&s, 1}, {l}, 1, empty, {samples, 1}).dense(1);
    EXPECT_NEAR(b[0], expected, 1e-6 * expected) << samples << " samples";  // float output
  }
}

}  // namespace test_polygon_irradiance
}  // namespace walk::compiler
