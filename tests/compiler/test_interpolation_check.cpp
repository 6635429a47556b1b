// The light stage's check of the light between vertices: which triangles it draws, and what it measures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "compiler/lighting/interpolation_check.hpp"

namespace walk::compiler {
namespace test_interpolation_check {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Two triangles on z = 0: a 2 x 2 one (area 2) and a 1 x 1 one (area 0.5), and a third whose corner 6 is
// not lit (a panel's, say).
struct Mesh {
  std::vector<Vec3> vertices{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {9, 0, 0}};
  std::vector<std::uint32_t> indices{0, 1, 2, 3, 4, 5, 4, 6, 5};
  std::vector<SurfaceSample> samples;
  std::vector<std::uint32_t> sample_vertex{0, 1, 2, 3, 4, 5};
  Mesh() {
    for (std::size_t v = 0; v < 6; ++v) samples.push_back({vertices[v], {0, 0, 1}, model::Rgb(0.5)});
  }
};

TEST(InterpolationCheck, DrawsLitTrianglesByAreaAtPointsInside) {
  const Mesh m;
  const auto checks = pick_interpolation_checks(m.samples, m.sample_vertex, m.vertices, m.indices, 5000, 7);
  ASSERT_EQ(checks.points.size(), 5000u);
  std::size_t large = 0;
  Vec3 large_mean(0.0);
  for (std::size_t k = 0; k < checks.points.size(); ++k) {
    EXPECT_NE(checks.corners[k][1], 6u) << "a triangle with an unlit corner is never drawn";
    const bool is_large = checks.corners[k][0] == 0;
    large += is_large;
    const auto& w = checks.weights[k];
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
    EXPECT_GE(std::min({w[0], w[1], w[2]}), 0.0) << "inside its triangle";
    Vec3 at(0.0);
    for (int i = 0; i < 3; ++i) at += m.vertices[checks.corners[k][i]] * w[i];
    EXPECT_NEAR(glm::length(checks.points[k].position - at), 0.0, 1e-12) << "the point its weights say";
    EXPECT_EQ(checks.points[k].normal, (Vec3{0, 0, 1}));
    if (is_large) large_mean += checks.points[k].position / 4000.0;
  }
  // Uniform over the large triangle: its points' mean is its centroid (standard error about 0.01 m).
  EXPECT_NEAR(glm::length(large_mean - Vec3{2.0 / 3, 2.0 / 3, 0}), 0.0, 0.05);
  // Area 2 against 0.5: 80 % of the draws, within five standard errors (0.57 %).
  EXPECT_NEAR(double(large) / 5000.0, 0.8, 0.03);
  const auto again = pick_interpolation_checks(m.samples, m.sample_vertex, m.vertices, m.indices, 5000, 7);
  EXPECT_EQ(again.corners, checks.corners) << "the same seed draws the same triangles";
  EXPECT_TRUE(pick_interpolation_checks(m.samples, {}, m.vertices, m.indices, 10, 7).points.empty());
}

TEST(InterpolationCheck, LinearLightIsExactAndABumpIsMeasured) {
  const Mesh m;
  const auto checks = pick_interpolation_checks(m.samples, m.sample_vertex, m.vertices, m.indices, 200, 3);
  // Light 1 + x + y at the vertices, one circuit: linear, so interpolating the corners is exact.
  SparseLight shown(m.vertices.size());
  auto light_at = [](const Vec3& p) { return 1.0 + p.x + p.y; };
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    *shown.at(v, 0) = *(shown.at(v, 0) + 1) = *(shown.at(v, 0) + 2) = light_at(m.vertices[v]);
  std::vector<double> truth;
  for (const auto& p : checks.points) truth.push_back(light_at(p.position));
  EXPECT_NEAR(interpolation_error(checks, shown, truth, 0.0, 0.0), 0.0, 1e-12);
  // A bump of a tenth at every point: 10 % relative at each check when the truth is that much darker.
  for (double& t : truth) t *= 1.0 / 1.1;
  EXPECT_NEAR(interpolation_error(checks, shown, truth, 0.0, 0.0), 0.1, 1e-9);
  // Noise that explains the whole difference leaves nothing; none of it, everything.
  EXPECT_EQ(interpolation_error(checks, shown, truth, 0.2, 0.0), 0.0);
  EXPECT_GT(interpolation_error(checks, shown, truth, 0.05, 0.0), 0.0);
  EXPECT_LT(interpolation_error(checks, shown, truth, 0.05, 0.0), 0.1);
  // The shown vertices' noise counts by the interpolation's squared weights (between 1/3 and 1), so it
  // takes out less than the same noise in the truth.
  const double truth_noisy = interpolation_error(checks, shown, truth, 0.06, 0.0);
  const double shown_noisy = interpolation_error(checks, shown, truth, 0.0, 0.06);
  EXPECT_LT(truth_noisy, shown_noisy);
  EXPECT_LT(shown_noisy, interpolation_error(checks, shown, truth, 0.0, 0.0));
  EXPECT_LT(shown_noisy, interpolation_error(checks, shown, truth, 0.06 / std::sqrt(3.0), 0.0) + 1e-12);
  // Points no view sees are left out: one far off among lit ones weighs nothing once hidden.
  std::vector<double> one_off(truth.size());
  std::vector<std::uint8_t> hidden(truth.size(), 0);
  for (std::size_t k = 0; k < truth.size(); ++k) one_off[k] = light_at(checks.points[k].position);
  one_off[17] = 0.0;
  hidden[17] = 1;
  EXPECT_GT(interpolation_error(checks, shown, one_off, 0.0, 0.0), 0.01);
  EXPECT_NEAR(interpolation_error(checks, shown, one_off, 0.0, 0.0, hidden), 0.0, 1e-12);
  // No light at all: nothing to be relative to.
  EXPECT_EQ(
      interpolation_error(checks, SparseLight(m.vertices.size()), std::vector<double>(200, 0.0), 0.0, 0.0),
      0.0);
}

}  // namespace test_interpolation_check
}  // namespace walk::compiler
