#include "compiler/lighting/path_reference.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>

#include "common/parallel_for.hpp"
#include "compiler/lighting/drawn_triangles.hpp"
#include "compiler/photometry/emission.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/luminaire_shapes.hpp"
#include "model/photometric_units.hpp"

namespace walk::compiler {
namespace {

// Rays leave a surface this far along its normal (metres): above round-off at building scale, below any
// real gap; the same offset the probe's and direct light's shadow rays use.
constexpr double kOffset = 1e-4;
// Hits closer than this (metres) are a tie between back-to-back copies of a wall: the facing one wins.
constexpr double kTie = 1e-6;
// Squared distance floor (m^2) of the inverse-square law, as in direct light: finite next to a luminaire.
constexpr double kMinDistanceSquared = 1e-4;
// Bounces before Russian roulette may end a path; it then survives with the hit's largest reflectance
// (at most kMaxSurvival, so a white room still ends).
constexpr int kSureBounces = 2;
constexpr double kMaxSurvival = 0.95;

// Cosine-distributed direction about unit n (Malley's method), its own basis.
model::Vec3 cosine_around(const model::Vec3& n, double u1, double u2) {
  const model::Vec3 helper = std::abs(n.x) < 0.9 ? model::Vec3(1, 0, 0) : model::Vec3(0, 1, 0);
  const model::Vec3 t = glm::normalize(glm::cross(helper, n));
  const model::Vec3 b = glm::cross(n, t);
  const double r = std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1.0 - u1));
}

// Radiant intensity per watt of a point, spot or fixture towards unit direction w (W/sr per W).
double point_intensity_per_watt(const model::Luminaire& l, const model::Vec3& w) {
  if (l.kind == model::LuminaireKind::Photometric) return photometric_intensity_per_watt(l, w);
  if (l.kind == model::LuminaireKind::Point) return 1.0 / (4.0 * std::numbers::pi);
  const double cone = std::min(l.cone, std::numbers::pi);
  const double c = glm::dot(glm::normalize(l.normal), w);
  if (c < std::cos(cone)) return 0.0;
  if (l.exponent <= 0.0) return 1.0 / (2.0 * std::numbers::pi * (1.0 - std::cos(cone)));
  const double lo = std::max(std::cos(cone), 0.0);
  return c <= 0.0 ? 0.0
                  : std::pow(c, l.exponent) * (l.exponent + 1.0) /
                        (2.0 * std::numbers::pi * (1.0 - std::pow(lo, l.exponent + 1.0)));
}

}  // namespace

std::vector<SurfacePoint> surface_points(const model::Bundle& b, std::size_t count) {
  const std::vector<TriangleCorners> triangles = drawn_triangles(b);
  std::vector<double> cumulative;
  double total = 0.0;
  const auto v = b.vertices();
  for (const auto& c : triangles) {
    const model::Vec3 a = vertex_position(v[c[0]]);
    total += 0.5 * glm::length(glm::cross(vertex_position(v[c[1]]) - a, vertex_position(v[c[2]]) - a));
    cumulative.push_back(total);
  }
  std::vector<SurfacePoint> out;
  if (triangles.empty()) return out;
  std::mt19937_64 rng(0x5eed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), u01(rng) * total);
    const auto& c = triangles[std::min<std::size_t>(it - cumulative.begin(), triangles.size() - 1)];
    const double s = std::sqrt(u01(rng)), t = u01(rng);
    SurfacePoint p{model::Vec3(0.0), model::Vec3(0.0), {}};
    const double weights[3] = {1.0 - s, s * (1.0 - t), s * t};
    for (int k = 0; k < 3; ++k) p.position += vertex_position(v[c[k]]) * weights[k];
    const auto& first = v[c[0]];
    p.normal = glm::normalize(vertex_normal(first));
    p.albedo = {first.albedo[0], first.albedo[1], first.albedo[2]};
    out.push_back(p);
  }
  return out;
}

struct PathTracer::Impl {
  std::unique_ptr<TriangleBvh> bvh;
  std::vector<model::Vec3> normal;  // per triangle, the side drawn
  std::vector<model::Rgb> albedo;   // per triangle
  std::vector<model::Luminaire> luminaires;
  std::vector<double> pick;  // cumulative scalar power, normalised
  std::vector<double> pick_probability;

  // Irradiance at x (unit normal n) from one luminaire drawn by power, with its shadow ray.
  model::Rgb next_event(const model::Vec3& x, const model::Vec3& n, std::mt19937_64& rng,
                        std::uint64_t& rays) const {
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    if (luminaires.empty()) return model::Rgb(0.0);
    const auto it = std::lower_bound(pick.begin(), pick.end(), u01(rng));
    const std::size_t i = std::min<std::size_t>(it - pick.begin(), luminaires.size() - 1);
    const auto& l = luminaires[i];
    const double p = pick_probability[i];
    if (p <= 0.0) return model::Rgb(0.0);
    double factor = 0.0;  // irradiance per watt of the luminaire
    model::Vec3 d;
    if (l.kind == model::LuminaireKind::Area) {
      const model::Vec3 ln = glm::normalize(l.normal);
      const model::Vec3 u = glm::normalize(l.u_axis);
      const model::Vec3 v = glm::normalize(glm::cross(ln, u));
      const model::Vec3 q = l.position + u * ((u01(rng) - 0.5) * l.width) + v * ((u01(rng) - 0.5) * l.height);
      d = q - x;
      const double r2 = std::max(glm::dot(d, d), kMinDistanceSquared), r = std::sqrt(r2);
      const double cos_x = glm::dot(n, d) / r, cos_e = -glm::dot(ln, d) / r;
      if (cos_x <= 0.0 || cos_e <= 0.0) return model::Rgb(0.0);
      factor = cos_x * cos_e / (std::numbers::pi * r2);  // Lambertian radiance Phi / (pi A), area pdf 1 / A
    } else {
      d = l.position - x;
      const double r2 = std::max(glm::dot(d, d), kMinDistanceSquared), r = std::sqrt(r2);
      const double cos_x = glm::dot(n, d) / r;
      if (cos_x <= 0.0) return model::Rgb(0.0);
      factor = point_intensity_per_watt(l, -d / r) * cos_x / r2;
      if (factor <= 0.0) return model::Rgb(0.0);
    }
    ++rays;
    // Stop short of an area light's own panel, which is among the occluders.
    const double reach = 1.0 - kOffset / std::max(std::sqrt(glm::dot(d, d)), 2.0 * kOffset);
    if (bvh->occluded(x, d, 0.0, reach)) return model::Rgb(0.0);
    return l.power * (factor / p);
  }
};

PathTracer::PathTracer(const model::Bundle& b) : impl_(std::make_unique<Impl>()) {
  std::vector<Triangle> triangles;
  const auto v = b.vertices();
  // Panels block and reflect as the solver's panels do; their glow comes by next event only.
  for (const auto& c : drawn_triangles(b, true)) {
    const auto& a = v[c[0]];
    triangles.push_back({vertex_position(a), vertex_position(v[c[1]]), vertex_position(v[c[2]]),
                         static_cast<std::uint32_t>(impl_->normal.size())});
    impl_->normal.push_back(glm::normalize(vertex_normal(a)));
    impl_->albedo.push_back({a.albedo[0], a.albedo[1], a.albedo[2]});
  }
  impl_->bvh = std::make_unique<TriangleBvh>(std::move(triangles));
  impl_->luminaires = model::load_luminaires(b);
  double total = 0.0;
  for (const auto& l : impl_->luminaires) total += (l.power.r + l.power.g + l.power.b) / 3.0;
  double running = 0.0;
  for (const auto& l : impl_->luminaires) {
    const double p = total > 0.0 ? (l.power.r + l.power.g + l.power.b) / 3.0 / total : 0.0;
    running += p;
    impl_->pick.push_back(running);
    impl_->pick_probability.push_back(p);
  }
  if (!impl_->pick.empty()) impl_->pick.back() = 1.0;
}

PathTracer::~PathTracer() = default;

PathReference PathTracer::trace(const std::vector<SurfacePoint>& points, int paths_per_point,
                                std::uint64_t seed, unsigned threads) const {
  const auto start = std::chrono::steady_clock::now();
  PathReference out;
  out.radiosity.assign(points.size(), model::Rgb(0.0));
  out.standard_error.assign(points.size(), 0.0);
  out.hidden.assign(points.size(), 0);
  std::atomic<std::uint64_t> rays{0};
  const Impl& m = *impl_;
  parallel_ranges(points.size(), 1, threads, [&](std::size_t first, std::size_t last) {
    std::uint64_t my_rays = 0;
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (std::size_t i = first; i < last; ++i) {
      std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + i);
      model::Rgb sum(0.0);
      double sum_y = 0.0, sum_y2 = 0.0;
      int backs = 0;
      for (int path = 0; path < paths_per_point; ++path) {
        model::Vec3 n = points[i].normal;
        model::Vec3 x = points[i].position + n * kOffset;
        model::Rgb throughput(1.0), irradiance(0.0);
        for (int depth = 0;; ++depth) {
          irradiance += throughput * m.next_event(x, n, rng, my_rays);
          const model::Vec3 dir = cosine_around(n, u01(rng), u01(rng));
          ++my_rays;
          const auto hit = m.bvh->closest_facing(x, dir, 0.0, 1e30, kTie);
          if (!hit) break;
          const std::uint32_t t = m.bvh->triangles()[hit->triangle].polygon;
          if (glm::dot(dir, m.normal[t]) >= 0.0) {  // the inside of a wall: dark
            backs += depth == 0;
            break;
          }
          throughput *= m.albedo[t];
          if (depth + 1 >= kSureBounces) {
            const double survive =
                std::min(kMaxSurvival, std::max({m.albedo[t].r, m.albedo[t].g, m.albedo[t].b}));
            if (u01(rng) >= survive) break;
            throughput /= survive;
          }
          n = m.normal[t];
          x = x + dir * hit->t + n * kOffset;
        }
        const model::Rgb radiosity = points[i].albedo * irradiance;
        sum += radiosity;
        const double y = model::luminance_weight(radiosity);
        sum_y += y;
        sum_y2 += y * y;
      }
      out.radiosity[i] = sum / double(paths_per_point);
      out.hidden[i] = 2 * backs > paths_per_point;
      const double mean = sum_y / paths_per_point;
      out.standard_error[i] =
          std::sqrt(std::max(0.0, sum_y2 / paths_per_point - mean * mean) / paths_per_point);
    }
    rays += my_rays;
  });
  out.rays = rays.load();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace walk::compiler
