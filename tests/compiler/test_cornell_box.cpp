// The measured Cornell box: our progressive shooter against an independent gathering reference.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>

#include "compiler/radiosity/validation/cornell_box.hpp"
#include "compiler/radiosity/validation/reference_solver.hpp"

namespace walk::compiler {
namespace test_cornell_box {  // named, not anonymous: the suite compiles as unity batches

const std::string kDir = std::string(WALK_SHARED_DATA) + "/cornell-box/";

CornellBox load() {
  return load_cornell_box(kDir + "cornell_box_geometry.txt", kDir + "reflectance_spectra.csv");
}

TEST(CornellBox, MeasuredDataLoadsWithInwardFacingRoom) {
  const CornellBox box = load();
  EXPECT_EQ(box.surfaces.size(), 16u);
  // Red wall reflects red most, green wall green most; white is near-flat (measured 0.7-0.75 in 500-700 nm).
  EXPECT_GT(box.red.r, 3.0 * box.red.g);
  EXPECT_GT(box.green.g, 2.0 * box.green.r);
  EXPECT_NEAR(box.white.g, box.white.r, 0.05);
  EXPECT_GT(box.emission.r, box.emission.b);  // the measured lamp is warm
  // Room surfaces face the box centre; block surfaces face away from their block.
  const model::Vec3 centre(0.278, 0.28, 0.274);
  std::vector<AreaEmitter> emitters;
  const PatchSet set = cornell_patches(box, 0.0, emitters);
  for (const auto& p : set.patches) {
    const auto& s = box.surfaces[p.polygon];
    const model::Vec3 c = (set.vertices[p.v[0]] + set.vertices[p.v[1]] + set.vertices[p.v[2]]) / 3.0;
    if (s.name.find("block") == std::string::npos) {
      EXPECT_GT(glm::dot(centre - c, p.normal), 0.0) << s.name;
    }
  }
  EXPECT_EQ(emitters.size(), 2u);
}

TEST(CornellBox, AnalyticFormFactorOfUnitSquaresMatchesCatalogue) {
  // Differential area at the centre of a unit square facing a parallel unit square at distance 1:
  // F = 4 * (1/(2 pi)) * (a/sqrt(1+a^2) atan(b/sqrt(1+a^2)) + ...) with a = b = 0.5 -> 0.2394 (Howell B-4).
  const std::vector<model::Vec3> square{{-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}};
  const double a = 0.5, b = 0.5;
  const double expected = 2.0 / 3.141592653589793 *
                          (a / std::sqrt(1 + a * a) * std::atan(b / std::sqrt(1 + a * a)) +
                           b / std::sqrt(1 + b * b) * std::atan(a / std::sqrt(1 + b * b)));
  EXPECT_NEAR(point_polygon_form_factor({0, 0, 0}, {0, 0, 1}, square), expected, 1e-12);
  // Edge-on and behind: zero, never NaN.
  EXPECT_EQ(point_polygon_form_factor({0, 0, 1}, {0, 0, 1}, square), 0.0);
  EXPECT_EQ(point_polygon_form_factor({0, 0, 2}, {0, 0, 1}, square), 0.0);
}

TEST(CornellBox, ShooterAgreesWithIndependentReference) {
  const CornellBox box = load();
  std::vector<AreaEmitter> emitters;
  const PatchSet set = cornell_patches(box, 0.1, emitters);
  ReferenceStats rs;
  const std::vector<double> ref = reference_radiosity(set, emitters, 2, &rs);
  RadiosityOptions o;
  o.rays_per_watt = 1.2e7;
  o.residual = 1e-3;
  const RadiosityResult r = solve_radiosity(set, emitters, {}, 1, o);
  // Relative radiosities: both normalised by their area-weighted mean over non-emitting patches.
  double mean_ref = 0.0, mean_ours = 0.0, area = 0.0;
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    if (box.surfaces[set.patches[i].polygon].material == "emitter") continue;
    for (int c = 0; c < 3; ++c) {
      mean_ref += set.patches[i].area * ref[i * 3 + c];
      mean_ours += set.patches[i].area * r.radiosity.value(i, std::size_t(c));
    }
    area += 3.0 * set.patches[i].area;
  }
  mean_ref /= area;
  mean_ours /= area;
  // Area-weighted: what a viewer sees; sliver patches at the trapezoidal floor's edge get few rays.
  double sq = 0.0, worst = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    if (box.surfaces[set.patches[i].polygon].material == "emitter") continue;
    for (int c = 0; c < 3; ++c) {
      const double d = r.radiosity.value(i, std::size_t(c)) / mean_ours - ref[i * 3 + c] / mean_ref;
      sq += set.patches[i].area * d * d;
      weight += set.patches[i].area;
      if (set.patches[i].area > 1e-3) worst = std::max(worst, std::abs(d));
    }
  }
  const double rms = std::sqrt(sq / weight);
  RecordProperty("rms_relative_error", std::to_string(rms));
  RecordProperty("patches", std::to_string(set.patches.size()));
  // Stated error, from measurement (docs/RADIOSITY.md): shooter noise at 3.3M rays is ~1.4% RMS and the
  // reference's quadrature error ~1.7%, so the area-weighted RMS of relative radiosity (in units of the mean)
  // stays within 3%.
  EXPECT_LT(rms, 0.03) << "rms " << rms << " worst " << worst;
  // Every surface brighter than a quarter of the mean agrees in total within 3%; absolute levels within 1%.
  std::map<std::uint32_t, std::array<double, 3>> surface;  // ours, reference, area
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    auto& s = surface[set.patches[i].polygon];
    for (int c = 0; c < 3; ++c) {
      s[0] += set.patches[i].area * r.radiosity.value(i, std::size_t(c));
      s[1] += set.patches[i].area * ref[i * 3 + c];
    }
    s[2] += 3.0 * set.patches[i].area;
  }
  for (const auto& [index, s] : surface) {
    if (s[1] / s[2] < 0.25 * mean_ref || box.surfaces[index].material == "emitter") continue;
    EXPECT_NEAR((s[0] / mean_ours) / (s[1] / mean_ref), 1.0, 0.03) << box.surfaces[index].name;
  }
  EXPECT_NEAR(mean_ours / mean_ref, 1.0, 0.01);
  std::printf("cornell: %zu patches, rms %.4f worst %.4f, shooter %.2f s %llu rays, reference %.2f s\n",
              set.patches.size(), rms, worst, r.stats.seconds, static_cast<unsigned long long>(r.stats.rays),
              rs.seconds);
}

}  // namespace test_cornell_box
}  // namespace walk::compiler
