// Direct light against the analytic irradiance of a small Lambertian panel, and shadowing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "compiler/lighting/direct_light.hpp"

namespace walk::compiler {
namespace test_direct_light {  // named, not anonymous: the suite compiles as unity batches

model::Luminaire panel_at(double z, double size) {
  model::Luminaire l;
  l.position = {0, 0, z};
  l.normal = {0, 0, -1};
  l.width = l.height = size;
  l.power = {100, 50, 10};
  l.circuit = 0;
  return l;
}

TEST(DirectLight, SmallPanelMatchesPointSourceLaw) {
  // Panel 0.1 m wide, 3 m above the sample: the far-field form E = Phi/(pi) * cos*cos / r^2 holds to ~0.1%.
  const SurfaceSample s{{0, 0, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
  const TriangleBvh empty({});
  const auto b = direct_light({&s, 1}, {panel_at(3.0, 0.1)}, 1, empty, {16, 1}).dense(1);
  const double expected = 0.5 * 100.0 / (std::numbers::pi * 9.0);
  EXPECT_NEAR(b[0], expected, 2e-3 * expected);
  EXPECT_NEAR(b[1] / b[0], 0.5, 1e-6);  // channels scale with the panel's colour
}

TEST(DirectLight, OccluderCastsShadowAndCircuitsStaySeparate) {
  const SurfaceSample s[2] = {{{0, 0, 0}, {0, 0, 1}, {1, 1, 1}}, {{5, 0, 0}, {0, 0, 1}, {1, 1, 1}}};
  // A 2 m square slab at z = 1 over the first sample only.
  std::vector<Triangle> slab{{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, 0},
                             {{-1, -1, 1}, {1, 1, 1}, {-1, 1, 1}, 0}};
  const TriangleBvh bvh(slab);
  model::Luminaire a = panel_at(2.0, 0.2);
  model::Luminaire b = panel_at(2.0, 0.2);
  b.position.x = 5.0;
  b.circuit = 1;
  DirectLightStats stats;
  const auto light = direct_light(s, {a, b}, 2, bvh, {9, 2}, &stats).dense(2);
  EXPECT_EQ(light[(0 * 2 + 0) * 3], 0.0f);  // sample 0 under the slab: circuit 0 blocked
  EXPECT_GT(light[(1 * 2 + 1) * 3], 0.0f);  // sample 1 lit by its own circuit 1
  EXPECT_GT(stats.occluded, 0u);
  for (float v : light) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
  // Shadowed wholly, circuit 0 leaves no entry at sample 0: a row holds only the light that reaches it.
  const SparseLight sparse = direct_light(s, {a, b}, 2, bvh, {9, 2});
  for (const auto& e : sparse.row(0)) EXPECT_NE(e.circuit, 0u);
  EXPECT_FALSE(sparse.row(1).empty());
}

TEST(DirectLight, SampleTouchingPanelStaysFinite) {
  const SurfaceSample s{{0, 0, 2.0 - 1e-9}, {1, 0, 0}, {1, 1, 1}};  // on the panel's plane, edge-on
  const TriangleBvh empty({});
  const auto b = direct_light({&s, 1}, {panel_at(2.0, 0.6)}, 1, empty, {16, 1}).dense(1);
  for (float v : b) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
}

TEST(DirectLight, ResultDoesNotDependOnThreadCount) {
  std::vector<SurfaceSample> samples;
  for (int i = 0; i < 1000; ++i) samples.push_back({{i * 0.01, 0, 0}, {0, 0, 1}, {0.7, 0.7, 0.7}});
  const TriangleBvh empty({});
  const auto one = direct_light(samples, {panel_at(2.5, 0.6)}, 1, empty, {8, 1}).dense(1);
  const auto two = direct_light(samples, {panel_at(2.5, 0.6)}, 1, empty, {8, 2}).dense(1);
  EXPECT_EQ(one, two);
}

}  // namespace test_direct_light
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_direct_light {  // named, not anonymous: the suite compiles as unity batches

TEST(DirectLight, PointAndSpotFollowTheInverseSquareLaw) {
  const SurfaceSample s{{0, 0, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
  const TriangleBvh empty({});
  model::Luminaire point;
  point.kind = model::LuminaireKind::Point;
  point.position = {0, 0, 2};
  point.power = model::Rgb(100.0);
  const auto b = direct_light({&s, 1}, {point}, 1, empty, {1, 1}).dense(1);
  const double isotropic = 0.5 * 100.0 / (4.0 * std::numbers::pi * 4.0);  // rho * Phi / (4 pi r^2)
  // Shadow rays start 0.1 mm off the surface, so r is 0.1 mm short: 1e-4 relative at 2 m, plus float output.
  constexpr double kOffsetError = 2e-4;
  EXPECT_NEAR(b[0], isotropic, kOffsetError * isotropic);

  // A 30-degree spot pointing down concentrates the same power into its cone: more light below it, none
  // outside the cone.
  model::Luminaire spot = point;
  spot.kind = model::LuminaireKind::Spot;
  spot.normal = {0, 0, -1};
  spot.cone = std::numbers::pi / 6.0;
  const auto below = direct_light({&s, 1}, {spot}, 1, empty, {1, 1}).dense(1);
  const double uniform_cone = 0.5 * 100.0 / (2.0 * std::numbers::pi * (1.0 - std::cos(spot.cone)) * 4.0);
  EXPECT_NEAR(below[0], uniform_cone, kOffsetError * uniform_cone);
  const SurfaceSample aside{{3, 0, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
  EXPECT_EQ(direct_light({&aside, 1}, {spot}, 1, empty, {1, 1}).dense(1)[0], 0.0f);
}

}  // namespace test_direct_light
}  // namespace walk::compiler
