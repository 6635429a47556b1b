// Progressive radiosity: analytic cases, energy balance and the hard cases that break naive solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <numbers>
#include <numeric>

#include "compiler/geometry/mesher.hpp"
#include "compiler/radiosity/progressive_solver.hpp"

namespace walk::compiler {
namespace test_radiosity {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Adds a planar quad (counter-clockwise about the normal it should have), diced at `grid` (0: two triangles).
// Returns the range of patches it produced.
std::pair<std::uint32_t, std::uint32_t> add_quad(PatchSet& set, const std::vector<Vec3>& corners, double rho,
                                                 double grid, std::uint32_t polygon = 0) {
  model::Polygon poly;
  poly.vertices = corners;
  const PolygonMesh mesh = mesh_polygon(poly, grid);
  const auto base = static_cast<std::uint32_t>(set.vertices.size());
  set.vertices.insert(set.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
  const auto first = static_cast<std::uint32_t>(set.patches.size());
  for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3)
    set.add(base + mesh.triangles[i], base + mesh.triangles[i + 1], base + mesh.triangles[i + 2],
            model::Rgb(rho), polygon);
  return {first, static_cast<std::uint32_t>(set.patches.size())};
}

// The six inward-facing faces of the box [lo, hi]; face order: -z floor, +z ceiling, -x, +x, -y, +y.
void add_box(PatchSet& set, Vec3 lo, Vec3 hi, double rho, double grid, bool with_ceiling = true) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  add_quad(set, {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}, rho, grid, 0);  // floor, normal +z
  if (with_ceiling) add_quad(set, {{x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}}, rho, grid, 1);
  add_quad(set, {{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}}, rho, grid,
           2);  // x0 wall, normal +x
  add_quad(set, {{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}}, rho, grid,
           3);  // x1 wall, normal -x
  add_quad(set, {{x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}}, rho, grid,
           4);  // y0 wall, normal +y
  add_quad(set, {{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}}, rho, grid,
           5);  // y1 wall, normal -y
}

double area_mean(const PatchSet& set, const RadiosityResult& r, std::size_t channel = 0) {
  double ab = 0.0, a = 0.0;
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    ab += set.patches[i].area * r.radiosity.value(i, channel);
    a += set.patches[i].area;
  }
  return ab / a;
}

void expect_energy_balance(const RadiosityStats& s) {
  const double accounted = s.absorbed + s.escaped + s.back_face + s.unshot;
  EXPECT_NEAR(accounted, s.emitted, 1e-9 * s.emitted) << "absorbed " << s.absorbed << " escaped " << s.escaped
                                                      << " back " << s.back_face << " unshot " << s.unshot;
}

void expect_finite_non_negative(const RadiosityResult& r) {
  for (std::size_t i = 0; i < r.radiosity.rows(); ++i)
    for (const auto& e : r.radiosity.row(i))
      for (double b : e.rgb) ASSERT_TRUE(std::isfinite(b) && b >= 0.0) << b;
}

std::vector<AreaEmitter> everything_emits(const PatchSet& set, double e) {
  std::vector<AreaEmitter> out;
  for (std::uint32_t i = 0; i < set.patches.size(); ++i) out.push_back({i, 0, model::Rgb(e)});
  return out;
}

TEST(Radiosity, WhiteFurnaceConvergesToClosedForm) {
  PatchSet set;
  add_box(set, Vec3(0), Vec3(1), 0.9, 0.5);
  RadiosityOptions o;
  o.rays_per_watt = 20000;
  o.residual = 1e-3;
  const auto r = solve_radiosity(set, everything_emits(set, 1.0), {}, 1, o);
  const double expected = 1.0 / (1.0 - 0.9);
  // Energy conservation makes the area mean exact up to the residual (rho * residual = 0.09%).
  EXPECT_NEAR(area_mean(set, r), expected, 0.01 * expected);
  // Each patch receives ~25k rays: Monte Carlo noise ~0.6%; 4 sigma.
  for (std::size_t i = 0; i < set.patches.size(); ++i)
    EXPECT_NEAR(r.radiosity.value(i, 0), expected, 0.025 * expected);
  EXPECT_EQ(r.stats.escaped, 0.0);
  EXPECT_EQ(r.stats.back_face, 0.0);
  expect_energy_balance(r.stats);
}

TEST(Radiosity, NearlyWhiteFurnaceStaysFiniteAndMonotone) {
  PatchSet set;
  add_box(set, Vec3(0), Vec3(1), 0.99, 0.5);
  RadiosityOptions o;
  o.rays_per_watt = 1000;
  o.residual = 0.05;
  std::vector<double> means;
  const auto r =
      solve_radiosity(set, everything_emits(set, 1.0), {}, 1, o,
                      [&](const RadiosityResult& partial) { means.push_back(area_mean(set, partial)); });
  ASSERT_GT(means.size(), 10u);
  for (std::size_t i = 1; i < means.size(); ++i) {
    ASSERT_TRUE(std::isfinite(means[i]));
    EXPECT_GE(means[i], means[i - 1]);
  }
  // Unshot 5% of emitted remains: B falls short of E/(1-rho) = 100 by at most rho * residual / (1 - rho).
  EXPECT_GT(means.back(), 100.0 * (1.0 - 0.99 * 0.05 / 0.01) - 1.0);
  EXPECT_LE(means.back(), 100.0 * 1.01);
  expect_finite_non_negative(r);
  expect_energy_balance(r.stats);
}

TEST(Radiosity, ParallelUnitSquaresMatchAnalyticFormFactor) {
  PatchSet set;
  // Emitter at z = 0 facing up (absorbs everything), receiver at z = 1 facing down (reflects everything).
  add_quad(set, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.0, 0.0, 0);
  const auto receiver = add_quad(set, {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, 1.0, 0.0, 1);
  std::vector<AreaEmitter> emit;
  for (std::uint32_t i = 0; i < receiver.first; ++i) emit.push_back({i, 0, model::Rgb(1.0)});
  RadiosityOptions o;
  o.rays_per_watt = 2e6;
  o.residual = 1e-6;
  const auto r = solve_radiosity(set, emit, {}, 1, o);
  // Two parallel unit squares one unit apart (Howell's catalogue C-11): F = 0.199825.
  double received = 0.0;
  for (std::uint32_t i = receiver.first; i < receiver.second; ++i)
    received += r.radiosity.value(i, 0) * set.patches[i].area;
  EXPECT_NEAR(received, 0.199825, 0.005 * 0.199825);  // 2M rays: sigma ~0.1%
  expect_energy_balance(r.stats);
}

// CIE 171:2006 test case 5.8 (the integrating-sphere relation in a cube): a 4 m cube, every surface of
// reflectance rho, an isotropic source of flux F at its centre: mean irradiance F / (S (1 - rho)), S = 96 m2.
// The case is in lumens and lux; the solver is linear, so 10,000 W gives the same numbers in W/m2:
// 104.17, 130.21, 208.33, 520.83 at rho 0, 0.2, 0.5, 0.8. Irradiance is radiosity / rho; rho = 0 is run as
// 1e-6 (what it reflects is a millionth, far below the tolerance).
TEST(Radiosity, Cie171CubeMeanIrradianceMatchesTheClosedForm) {
  constexpr double kFlux = 10000.0, kSide = 4.0, kArea = 6.0 * kSide * kSide;
  for (const double rho : {0.0, 0.2, 0.5, 0.8}) {
    const double r = std::max(rho, 1e-6);
    PatchSet set;
    add_box(set, Vec3(0), Vec3(kSide), r, 1.0);
    PointEmitter source;
    source.position = Vec3(kSide / 2.0);
    source.power = model::Rgb(kFlux);
    RadiosityOptions o;
    o.rays_per_watt = 20.0;  // 200,000 rays from the source
    o.residual = 1e-4;       // what is left unshot would lower the mean by rho * 1e-4 / (1 - rho)
    const auto result = solve_radiosity(set, {}, std::span<const PointEmitter>(&source, 1), 1, o);
    const double irradiance = area_mean(set, result) / r;
    const double expected = kFlux / (kArea * (1.0 - rho));
    std::printf("CIE 171 5.8, rho %.1f: %.2f W/m2, closed form %.2f, error %+.3f %%\n", rho, irradiance,
                expected, 100.0 * (irradiance / expected - 1.0));
    EXPECT_NEAR(irradiance, expected, 0.02 * expected) << "rho " << rho;
    expect_energy_balance(result.stats);
  }
}

// The same cube with the source's direct light gathered (its closed form at each patch's corners, as the
// light stage gathers it at vertices) and only reflected light shot: the mean is the same closed form, the
// energy books balance over the injected power, and the estimate counts the shot light only.
TEST(Radiosity, GatheredDirectLightGivesTheCie171MeanAndBalances) {
  constexpr double kFlux = 10000.0, kSide = 4.0, kArea = 6.0 * kSide * kSide, kRho = 0.5;
  PatchSet set;
  add_box(set, Vec3(0), Vec3(kSide), kRho, 0.5);
  const Vec3 source(kSide / 2.0);
  std::vector<double> direct;  // [patch][channel]: rho * I cos / r^2 averaged over the corners
  for (const auto& p : set.patches) {
    double e = 0.0;
    for (const std::uint32_t v : p.v) {
      const Vec3 d = source - set.vertices[v];
      const double r2 = glm::dot(d, d);
      e += kFlux / (4.0 * std::numbers::pi) * glm::dot(p.normal, d) / std::sqrt(r2) / r2 / 3.0;
    }
    direct.insert(direct.end(), 3, kRho * e);
  }
  RadiosityOptions o;
  o.rays_per_watt = 40.0;
  o.residual = 1e-4;
  const SparseLight gathered = SparseLight::from_dense(direct, 1);
  o.gathered_direct = &gathered;
  PointEmitter point;  // shoots nothing: its light is the gathered one
  point.position = source;
  point.power = model::Rgb(kFlux);
  const auto r = solve_radiosity(set, {}, std::span<const PointEmitter>(&point, 1), 1, o);
  const double irradiance = area_mean(set, r) / kRho;
  const double expected = kFlux / (kArea * (1.0 - kRho));
  std::printf("CIE 171 5.8 with gathered direct light: %.2f W/m2, closed form %.2f, estimate %.2f %%\n",
              irradiance, expected, 100.0 * r.stats.estimated_error);
  // The corner mean of a smooth 1/r^2 light over 0.5 m patches is within about 1 % of its area mean.
  EXPECT_NEAR(irradiance, expected, 0.02 * expected);
  // Injected: the reflected direct power, rho * flux (every ray of the source meets a wall).
  EXPECT_NEAR(r.stats.emitted, kRho * kFlux, 0.02 * kRho * kFlux);
  expect_energy_balance(r.stats);
  EXPECT_EQ(r.stats.escaped, 0.0);
  EXPECT_GT(r.stats.estimated_error, 0.0);
  EXPECT_LT(r.stats.estimated_error, 0.2);
  const SparseLight short_one =
      SparseLight::from_dense(std::span<const double>(direct.data(), direct.size() - 3), 1);
  o.gathered_direct = &short_one;
  EXPECT_THROW((void)solve_radiosity(set, {}, {}, 1, o), std::invalid_argument) << "one patch short";
}

// Irradiance at (px, py, 0) from a Lambertian rectangle [x0, x1] x [y0, y1] at height h facing down, per unit
// exitance: the configuration factor from a point to a parallel rectangle with a corner above it (Howell's
// catalogue B-3), added and taken away over the four corners, signs for a point outside the rectangle.
double rectangle_factor(double px, double py, double x0, double x1, double y0, double y1, double h) {
  auto corner = [h](double u, double v) {
    const double a = std::abs(u) / h, b = std::abs(v) / h;
    const double f = (a / std::sqrt(1 + a * a) * std::atan(b / std::sqrt(1 + a * a)) +
                      b / std::sqrt(1 + b * b) * std::atan(a / std::sqrt(1 + b * b))) /
                     (2.0 * 3.141592653589793);
    return (u < 0) != (v < 0) ? -f : f;
  };
  return corner(x1 - px, y1 - py) - corner(x0 - px, y1 - py) - corner(x1 - px, y0 - py) +
         corner(x0 - px, y0 - py);
}

// Direct irradiance under a rectangular Lambertian source (2 m x 1 m, 1 m up), on 30 cm receivers centred
// below a corner and below the centre, against the closed form averaged over each receiver (21 x 21 points).
TEST(Radiosity, RectangularSourceIrradianceBelowCornerAndCentreMatchesTheClosedForm) {
  constexpr double kHeight = 1.0, kHalf = 0.15;
  PatchSet set;
  add_quad(set, {{0, 0, kHeight}, {0, 1, kHeight}, {2, 1, kHeight}, {2, 0, kHeight}}, 0.0, 0.0,
           0);  // faces down
  struct Receiver {
    double x, y;
    std::pair<std::uint32_t, std::uint32_t> patches;
  };
  std::vector<Receiver> receivers{{0.0, 0.0, {}}, {1.0, 0.5, {}}};
  for (auto& rc : receivers)
    rc.patches = add_quad(set,
                          {{rc.x - kHalf, rc.y - kHalf, 0},
                           {rc.x + kHalf, rc.y - kHalf, 0},
                           {rc.x + kHalf, rc.y + kHalf, 0},
                           {rc.x - kHalf, rc.y + kHalf, 0}},
                          1.0, 0.0, 1);  // faces up, reflects all it gets: radiosity is irradiance
  std::vector<AreaEmitter> emit{{0, 0, model::Rgb(1.0)}, {1, 0, model::Rgb(1.0)}};
  RadiosityOptions o;
  o.rays_per_watt = 1e7;  // 20 M rays: about 150,000 reach the corner receiver, sigma 0.26 %
  const auto r = solve_radiosity(set, emit, {}, 1, o);
  for (const auto& rc : receivers) {
    double received = 0.0, area = 0.0;
    for (std::uint32_t i = rc.patches.first; i < rc.patches.second; ++i) {
      received += r.radiosity.value(i, 0) * set.patches[i].area;
      area += set.patches[i].area;
    }
    constexpr int kSteps = 21;
    double expected = 0.0;
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; j < kSteps; ++j)
        expected += rectangle_factor(rc.x - kHalf + 2 * kHalf * (i + 0.5) / kSteps,
                                     rc.y - kHalf + 2 * kHalf * (j + 0.5) / kSteps, 0, 2, 0, 1, kHeight);
    expected /= kSteps * kSteps;
    std::printf("rectangle source, receiver at (%.1f, %.1f): %.5f, closed form %.5f, error %+.3f %%\n", rc.x,
                rc.y, received / area, expected, 100.0 * (received / area / expected - 1.0));
    EXPECT_NEAR(received / area, expected, 0.02 * expected);
  }
  // The point values themselves, as the catalogue gives them: below a corner 0.16737, below the centre
  // four corners of 1 m x 0.5 m, 0.36074.
  EXPECT_NEAR(rectangle_factor(0, 0, 0, 2, 0, 1, 1), 0.16737, 1e-5);
  EXPECT_NEAR(rectangle_factor(1, 0.5, 0, 2, 0, 1, 1), 0.36074, 1e-5);
  EXPECT_NEAR(rectangle_factor(3, 0.5, 0, 2, 0, 1, 1) + rectangle_factor(3, 0.5, 2, 3, 0, 1, 1),
              rectangle_factor(3, 0.5, 0, 3, 0, 1, 1), 1e-12)
      << "superposition holds for a point outside the rectangle";
}

TEST(Radiosity, OpenBoxBalancesEnergyAndLightEscapes) {
  PatchSet set;
  add_box(set, Vec3(0), Vec3(2, 2, 1), 0.6, 0.5, /*with_ceiling=*/false);
  const auto lamp =
      add_quad(set, {{0.8, 0.8, 0.9}, {0.8, 1.2, 0.9}, {1.2, 1.2, 0.9}, {1.2, 0.8, 0.9}}, 0.8, 0.0, 9);
  std::vector<AreaEmitter> emit;
  for (std::uint32_t i = lamp.first; i < lamp.second; ++i) emit.push_back({i, 0, {100.0, 50.0, 25.0}});
  RadiosityOptions o;
  o.rays_per_watt = 2000;
  const auto r = solve_radiosity(set, emit, {}, 1, o);
  EXPECT_GT(r.stats.escaped, 0.0);
  EXPECT_LE(r.stats.unshot, 0.01 * r.stats.emitted);
  expect_energy_balance(r.stats);
  expect_finite_non_negative(r);
}

TEST(Radiosity, BackToBackWallsDoNotLeakIntoTheNextRoom) {
  // Two closed rooms sharing the plane x = 2, each drawn with its own wall copy (as EnergyPlus does), and
  // both drawn from separately diced faces: only room A has a lamp, on circuit 1 of 2.
  PatchSet set;
  add_box(set, Vec3(0, 0, 0), Vec3(2, 2, 2.5), 0.7, 0.35);
  const auto room_b_first = static_cast<std::uint32_t>(set.patches.size());
  add_box(set, Vec3(2, 0, 0), Vec3(4, 2, 2.5), 0.7, 0.35);
  const auto lamp =
      add_quad(set, {{0.7, 0.7, 2.49}, {0.7, 1.3, 2.49}, {1.3, 1.3, 2.49}, {1.3, 0.7, 2.49}}, 0.8, 0.0);
  std::vector<AreaEmitter> emit;
  for (std::uint32_t i = lamp.first; i < lamp.second; ++i) emit.push_back({i, 1, model::Rgb(200.0)});
  RadiosityOptions o;
  o.rays_per_watt = 500;
  const auto r = solve_radiosity(set, emit, {}, 2, o);
  for (std::uint32_t i = room_b_first; i < lamp.first; ++i)
    for (int k = 0; k < 6; ++k)
      ASSERT_EQ(r.radiosity.value(i, std::size_t(k)), 0.0) << "patch " << i << " of room B lit";
  for (std::uint32_t i = 0; i < room_b_first; ++i)
    EXPECT_EQ(r.radiosity.value(i, 0), 0.0);  // circuit 0: no emitter
  EXPECT_EQ(r.stats.escaped, 0.0);
  // The only back faces rays can meet are the top of the one-sided lamp, seen from the ceiling 1 cm above.
  EXPECT_LT(r.stats.back_face, 0.01 * r.stats.emitted);
  expect_energy_balance(r.stats);
}

TEST(Radiosity, SliversTinyPatchesAndFlushLuminaireStayFinite) {
  PatchSet set;
  // Floor split into a wide quad and a 0.1 mm sliver, touching and coplanar; a 1 cm^2 tile; walls; and a
  // luminaire flush with (coplanar to) the ceiling.
  add_quad(set, {{0, 0, 0}, {1.9999, 0, 0}, {1.9999, 2, 0}, {0, 2, 0}}, 0.5, 0.25);
  add_quad(set, {{1.9999, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1.9999, 2, 0}}, 0.5, 0.25);
  add_quad(set, {{1, 1, 0.001}, {1.01, 1, 0.001}, {1.01, 1.01, 0.001}, {1, 1.01, 0.001}}, 0.5, 0.0);
  add_quad(set, {{0, 0, 2}, {0, 2, 2}, {2, 2, 2}, {2, 0, 2}}, 0.8, 0.25);
  add_quad(set, {{0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}}, 0.5, 0.25);
  add_quad(set, {{2, 0, 0}, {2, 0, 2}, {2, 2, 2}, {2, 2, 0}}, 0.5, 0.25);
  add_quad(set, {{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}}, 0.5, 0.25);
  add_quad(set, {{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}}, 0.5, 0.25);
  const auto lamp = add_quad(set, {{0.7, 0.7, 2}, {0.7, 1.3, 2}, {1.3, 1.3, 2}, {1.3, 0.7, 2}}, 0.8, 0.0);
  std::vector<AreaEmitter> emit;
  for (std::uint32_t i = lamp.first; i < lamp.second; ++i) emit.push_back({i, 0, model::Rgb(300.0)});
  RadiosityOptions o;
  o.rays_per_watt = 1000;
  const auto r = solve_radiosity(set, emit, {}, 1, o);
  expect_finite_non_negative(r);
  expect_energy_balance(r.stats);
  EXPECT_EQ(r.stats.escaped, 0.0) << "light leaked through a joint";
  EXPECT_GT(r.radiosity.value(0, 0), 0.0);  // the floor is lit
}

TEST(Radiosity, SpotLightsOnlyItsConeAndKeepsItsPower) {
  PatchSet set;
  add_box(set, Vec3(-3, -3, 0), Vec3(3, 3, 3), 0.0, 0.5);  // black walls and ceiling: they reflect nothing
  for (auto& p : set.patches)
    if (p.normal.z > 0.5) p.reflectance = model::Rgb(0.5);  // the floor cannot see itself: only direct light
  PointEmitter spot;
  spot.position = {0, 0, 2.9};
  spot.axis = {0, 0, -1};
  spot.cone = 20.0 * 3.141592653589793 / 180.0;
  spot.exponent = 4.0;
  spot.power = model::Rgb(100.0);
  RadiosityOptions o;
  o.rays_per_watt = 2000;
  const auto r = solve_radiosity(set, {}, std::span<const PointEmitter>(&spot, 1), 1, o);
  const double footprint = 2.9 * std::tan(spot.cone) + 0.75;  // cone radius on the floor plus one patch
  std::size_t lit = 0;
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    const auto& p = set.patches[i];
    if (p.normal.z < 0.5) continue;
    const Vec3 c = (set.vertices[p.v[0]] + set.vertices[p.v[1]] + set.vertices[p.v[2]]) / 3.0;
    if (std::hypot(c.x, c.y) > footprint) {
      EXPECT_EQ(r.radiosity.value(i, 0), 0.0) << "patch " << i << " outside the cone";
    }
    lit += r.radiosity.value(i, 0) > 0.0;
  }
  EXPECT_GT(lit, 4u);
  EXPECT_EQ(r.stats.escaped, 0.0);
  EXPECT_GE(r.stats.absorbed, 99.0);  // closed room: all but the 1% residual is absorbed
  expect_energy_balance(r.stats);
}

TEST(Radiosity, SameResultForOneAndTwoThreads) {
  PatchSet set;
  add_box(set, Vec3(0), Vec3(2, 3, 2.5), 0.6, 0.5);
  std::vector<AreaEmitter> emit{{0, 0, model::Rgb(50.0)}};
  RadiosityOptions o;
  o.rays_per_watt = 3000;
  o.threads = 1;
  const auto one = solve_radiosity(set, emit, {}, 1, o);
  o.threads = 2;
  const auto two = solve_radiosity(set, emit, {}, 1, o);
  EXPECT_EQ(one.radiosity.dense(1), two.radiosity.dense(1));
}

}  // namespace test_radiosity
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_radiosity {  // named, not anonymous: the suite compiles as unity batches

// The area-weighted relative RMS difference of two solutions' scalar radiosity, as estimated_error defines it
// (patches in `emitting` left out: their own glow is exact).
double relative_rms(const PatchSet& set, const RadiosityResult& a, const RadiosityResult& ref,
                    const std::vector<AreaEmitter>& emitting) {
  std::vector<bool> skip(set.patches.size(), false);
  for (const auto& e : emitting) skip[e.patch] = true;
  double diff = 0.0, square = 0.0;
  const std::size_t k = ref.circuits * 3;
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    double x = 0.0, y = 0.0;
    for (std::size_t j = 0; j < k; ++j) {
      x += a.radiosity.value(i, j) / 3.0;
      y += ref.radiosity.value(i, j) / 3.0;
    }
    if (skip[i]) continue;
    diff += set.patches[i].area * (x - y) * (x - y);
    square += set.patches[i].area * y * y;
  }
  return std::sqrt(diff / square);
}

TEST(Radiosity, ErrorEstimateTracksTheMeasuredError) {
  // A 4 x 3 x 2.5 m room (rho 0.6, 0.25 m patches) lit by a spot and a ceiling panel on two circuits; the
  // estimate at each ray count against the error measured from a solve with 64 times the rays (whose own
  // error, an eighth as large, is taken out in quadrature).
  PatchSet set;
  add_box(set, Vec3(0), Vec3(4, 3, 2.5), 0.6, 0.25);
  std::vector<AreaEmitter> panel;
  for (std::uint32_t i = 0; i < set.patches.size(); ++i) {
    const auto& p = set.patches[i];
    const Vec3 c = (set.vertices[p.v[0]] + set.vertices[p.v[1]] + set.vertices[p.v[2]]) / 3.0;
    if (p.normal.z < -0.5 && std::abs(c.x - 1.0) < 0.3 && std::abs(c.y - 1.5) < 0.3)
      panel.push_back({i, 0, model::Rgb(100.0)});
  }
  ASSERT_FALSE(panel.empty());
  PointEmitter spot;
  spot.position = {3, 1.5, 2.4};
  spot.cone = 0.6;
  spot.exponent = 2.0;
  spot.power = model::Rgb(30.0);
  spot.circuit = 1;
  RadiosityOptions o;
  o.residual = 1e-3;
  auto solve = [&](double rays_per_watt) {
    o.rays_per_watt = rays_per_watt;
    return solve_radiosity(set, panel, std::span<const PointEmitter>(&spot, 1), 2, o);
  };
  const auto reference = solve(64 * 400.0);
  double previous = 1.0;
  for (const double rays_per_watt : {50.0, 400.0}) {
    const auto r = solve(rays_per_watt);
    const double measured = std::sqrt(std::max(0.0, std::pow(relative_rms(set, r, reference, panel), 2) -
                                                        std::pow(reference.stats.estimated_error, 2)));
    std::printf("rays/W %.0f: estimated error %.2f %%, measured %.2f %%\n", rays_per_watt,
                100.0 * r.stats.estimated_error, 100.0 * measured);
    EXPECT_GT(r.stats.estimated_error, 0.6 * measured) << rays_per_watt;
    EXPECT_LT(r.stats.estimated_error, 1.6 * measured) << rays_per_watt;
    EXPECT_LT(r.stats.estimated_error, previous);  // more rays, smaller estimate
    previous = r.stats.estimated_error;
  }
}

}  // namespace test_radiosity
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_radiosity {  // named, not anonymous: the suite compiles as unity batches

// An emitter on a circuit the solve was not given is a caller's error, said before a ray is cast: a sparse
// row would otherwise hold a circuit no bundle record names.
TEST(Radiosity, AnEmitterBeyondTheCircuitCountIsRefused) {
  PatchSet set;
  add_box(set, Vec3(0), Vec3(2, 3, 2.5), 0.6, 0.5);
  const std::vector<AreaEmitter> emit{{0, 1, model::Rgb(50.0)}};
  EXPECT_THROW((void)solve_radiosity(set, emit, {}, 1, RadiosityOptions{}), std::invalid_argument);
  PointEmitter point;
  point.position = Vec3(1.0, 1.5, 1.2);
  point.power = model::Rgb(10.0);
  point.circuit = 3;
  EXPECT_THROW(
      (void)solve_radiosity(set, {}, std::span<const PointEmitter>(&point, 1), 2, RadiosityOptions{}),
      std::invalid_argument);
}

}  // namespace test_radiosity
}  // namespace walk::compiler
