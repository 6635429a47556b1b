#include "compiler/lighting/direct_light.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>
#include <stdexcept>

#include "common/parallel_for.hpp"
#include "compiler/lighting/polygon_irradiance.hpp"
#include "compiler/photometry/emission.hpp"

namespace walk::compiler {
namespace {

// Shadow rays start this far off the surface along its normal, metres: above double round-off at building
// scale (1e-12 m) and far below any gap a real building has, so coincident back-to-back walls never
// self-shadow.
constexpr double kShadowOffset = 1e-4;
// Squared distance floor, m^2: keeps the inverse-square law finite for samples touching a luminaire.
constexpr double kMinDistanceSquared = 1e-4;

// Stratified (jittered) points on the luminaire rectangle: sqrt(n) x sqrt(n) strata when n is square.
void panel_points(const model::Luminaire& l, int n, std::mt19937_64& rng, std::vector<model::Vec3>& out) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(double(n)))));
  const int cols = side, rows = (n + side - 1) / side;
  const model::Vec3 u = glm::normalize(l.u_axis);
  const model::Vec3 v = glm::normalize(glm::cross(l.normal, u));
  out.clear();
  for (int i = 0; i < n; ++i) {
    const double su = ((i % cols) + u01(rng)) / cols - 0.5;
    const double sv = ((i / cols) + u01(rng)) / rows - 0.5;
    out.push_back(l.position + u * (su * l.width) + v * (sv * l.height));
  }
}

// Radiant intensity per watt of a point light towards unit direction `w` (W/sr per W): its measured table,
// uniform over the sphere, or cos^n about the axis inside the cone, normalised so the light emits exactly its
// power.
double intensity_per_watt(const model::Luminaire& l, const model::Vec3& w) {
  if (l.kind == model::LuminaireKind::Photometric) return photometric_intensity_per_watt(l, w);
  const double cone =
      l.kind == model::LuminaireKind::Spot ? std::min(l.cone, std::numbers::pi) : std::numbers::pi;
  const double n = l.kind == model::LuminaireKind::Spot ? l.exponent : 0.0;
  const double c = glm::dot(glm::normalize(l.normal), w);
  const double cos_cone = std::cos(cone);
  if (c < cos_cone) return 0.0;
  if (n <= 0.0) return 1.0 / (2.0 * std::numbers::pi * (1.0 - cos_cone));
  const double lo = std::max(cos_cone, 0.0);
  if (c <= 0.0) return 0.0;
  // Integral of cos^n over the cone's solid angle: 2 pi (1 - lo^(n+1)) / (n+1).
  return std::pow(c, n) * (n + 1.0) / (2.0 * std::numbers::pi * (1.0 - std::pow(lo, n + 1.0)));
}

void add_point_light(const SurfaceSample& p, const model::Vec3& origin, const model::Luminaire& l,
                     const TriangleBvh& occluders, SparseLight& out, std::size_t row, std::uint64_t& rays,
                     std::uint64_t& blocked) {
  const model::Vec3 d = l.position - origin;
  const double r2 = std::max(glm::dot(d, d), kMinDistanceSquared);
  const double r = std::sqrt(r2);
  const double cos_r = glm::dot(p.normal, d) / r;
  if (cos_r <= 0.0) return;
  const double intensity = intensity_per_watt(l, -d / r);
  if (intensity <= 0.0) return;
  ++rays;
  if (occluders.occluded(origin, d, 0.0, 1.0)) {
    ++blocked;
    return;
  }
  double* b = out.at(row, l.circuit);
  for (int c = 0; c < 3; ++c) b[c] += p.albedo[c] * l.power[c] * intensity * cos_r / r2;
}

}  // namespace

SparseLight direct_light(std::span<const SurfaceSample> samples,
                         const std::vector<model::Luminaire>& luminaires, std::size_t circuit_count,
                         const TriangleBvh& occluders, const DirectLightOptions& options,
                         DirectLightStats* stats) {
  for (const auto& l : luminaires)
    if (l.circuit >= circuit_count)
      throw std::invalid_argument("direct_light: luminaire circuit out of range");
  SparseLight out(samples.size());
  std::atomic<std::uint64_t> rays{0}, blocked{0};
  constexpr std::size_t kChunk = 256;
  parallel_ranges(samples.size(), kChunk, options.threads, [&](std::size_t begin, std::size_t end) {
    std::vector<model::Vec3> points;
    std::uint64_t my_rays = 0, my_blocked = 0;
    {
      for (std::size_t s = begin; s < end; ++s) {
        const SurfaceSample& p = samples[s];
        std::mt19937_64 rng(0x9e3779b97f4a7c15ull ^ s);  // per sample: same result for any thread count
        const model::Vec3 origin = p.position + p.normal * kShadowOffset;
        for (const auto& l : luminaires) {
          if (l.kind != model::LuminaireKind::Area) {
            add_point_light(p, origin, l, occluders, out, s, my_rays, my_blocked);
            continue;
          }
          const model::Vec3 ln = glm::normalize(l.normal);
          if (glm::dot(p.position - l.position, ln) <= 0.0) continue;  // behind the panel
          panel_points(l, options.samples_per_luminaire, rng, points);
          // The samples judge only how much of the panel is shadowed (each weighted by what it would
          // bring); the unshadowed light is the panel's exact projected solid angle.
          double weight = 0.0, visible = 0.0;
          for (const auto& q : points) {
            const model::Vec3 d = q - origin;
            const double r2 = std::max(glm::dot(d, d), kMinDistanceSquared);
            const double r = std::sqrt(r2);
            const double cos_r = glm::dot(p.normal, d) / r;
            const double cos_e = -glm::dot(ln, d) / r;
            if (cos_r <= 0.0 || cos_e <= 0.0) continue;
            const double w = cos_r * cos_e / r2;
            weight += w;
            ++my_rays;
            if (occluders.occluded(origin, d, 0.0, 1.0)) {
              ++my_blocked;
              continue;
            }
            visible += w;
          }
          // No sample in front of the receiver: only a sliver of the panel is, too little to shadow-test.
          if (visible <= 0.0) continue;  // also every sample shadowed: no entry
          // Lambertian panel: radiance Phi / (pi A).
          const double irradiance_per_watt =
              projected_solid_angle(model::panel_corners(l), origin, p.normal) * (visible / weight) /
              (std::numbers::pi * l.width * l.height);
          if (irradiance_per_watt <= 0.0) continue;  // every point shadowed or turned away: no entry
          double* b = out.at(s, l.circuit);
          for (int c = 0; c < 3; ++c) b[c] += p.albedo[c] * l.power[c] * irradiance_per_watt;
        }
      }
    }
    rays += my_rays;
    blocked += my_blocked;
  });
  if (stats) *stats = {rays.load(), blocked.load()};
  return out;
}

}  // namespace walk::compiler
