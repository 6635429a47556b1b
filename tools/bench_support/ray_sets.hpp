#pragma once
// Ray sets for the ray-casting tests and benchmark, reproducible from a seed:
// - primary: pinhole views (90 degree field, square) from eye points inside the model's bounds;
// - radiosity: from area-weighted random surface points, cosine-distributed about the front normal;
// - occlusion: segments between two random surface points (form-factor visibility);
// - random: uniform origins in the bounds, uniform directions.
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::bench {

using compiler::Ray;
using compiler::Triangle;

class SurfaceSampler {
 public:
  explicit SurfaceSampler(const std::vector<Triangle>& tris) : tris_(tris) {
    double sum = 0.0;
    for (const auto& t : tris) {
      sum += 0.5 * glm::length(glm::cross(t.b - t.a, t.c - t.a));
      cdf_.push_back(sum);
    }
  }
  // A point on a triangle chosen by area, and that triangle's unit front normal.
  template <class Rng>
  void sample(Rng& rng, model::Vec3& p, model::Vec3& n) const {
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    const double x = u01(rng) * cdf_.back();
    const auto i = static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
    const Triangle& t = tris_[std::min(i, tris_.size() - 1)];
    double s = u01(rng), r = u01(rng);
    if (s + r > 1.0) {
      s = 1.0 - s;
      r = 1.0 - r;
    }
    p = t.a + s * (t.b - t.a) + r * (t.c - t.a);
    n = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
  }

 private:
  const std::vector<Triangle>& tris_;
  std::vector<double> cdf_;
};

inline model::Bounds triangle_bounds(const std::vector<Triangle>& tris) {
  model::Bounds b;
  for (const auto& t : tris) {
    b.add(t.a);
    b.add(t.b);
    b.add(t.c);
  }
  return b;
}

inline std::vector<Ray> primary_rays(const std::vector<Triangle>& tris, std::size_t count, unsigned seed,
                                     int eyes = 16) {
  std::mt19937_64 rng(seed);
  const model::Bounds b = triangle_bounds(tris);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(count) / eyes)));
  std::vector<Ray> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    model::Vec3 eye;
    for (int a = 0; a < 3; ++a) eye[a] = b.min[a] + (0.1 + 0.8 * u01(rng)) * (b.max[a] - b.min[a]);
    const double yaw = 2.0 * std::numbers::pi * u01(rng);
    const model::Vec3 fwd(std::cos(yaw), std::sin(yaw), 0.0), right(std::sin(yaw), -std::cos(yaw), 0.0);
    const model::Vec3 up(0.0, 0.0, 1.0);
    for (std::size_t y = 0; y < side && rays.size() < count; ++y)
      for (std::size_t x = 0; x < side && rays.size() < count; ++x) {
        const double sx = (2.0 * (x + 0.5) / side - 1.0), sy = (2.0 * (y + 0.5) / side - 1.0);
        rays.push_back({eye, glm::normalize(fwd + sx * right + sy * up), 0.0, INFINITY});
      }
  }
  return rays;
}

inline std::vector<Ray> radiosity_rays(const std::vector<Triangle>& tris, std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const SurfaceSampler s(tris);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    model::Vec3 p, n;
    s.sample(rng, p, n);
    // Cosine-weighted direction about n (Malley: uniform disc lifted to the hemisphere).
    const double r = std::sqrt(u01(rng)), phi = 2.0 * std::numbers::pi * u01(rng);
    const model::Vec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, model::Vec3(1, 0, 0))
                                                             : glm::cross(n, model::Vec3(0, 1, 0)));
    const model::Vec3 bt = glm::cross(n, t);
    const model::Vec3 d =
        r * std::cos(phi) * t + r * std::sin(phi) * bt + std::sqrt(std::max(0.0, 1.0 - r * r)) * n;
    rays.push_back({p, d, compiler::self_hit_tmin(d), INFINITY});
  }
  return rays;
}

inline std::vector<Ray> occlusion_rays(const std::vector<Triangle>& tris, std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  const SurfaceSampler s(tris);
  std::vector<Ray> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    model::Vec3 p, q, np, nq;
    s.sample(rng, p, np);
    s.sample(rng, q, nq);
    const model::Vec3 d = q - p;
    const double len = glm::length(d);
    if (!(len > 4.0 * compiler::kSelfHitDistance)) continue;
    // Leave the surface on the side the segment goes to; stop short of the far surface.
    rays.push_back({p, d, compiler::kSelfHitDistance / len, 1.0 - compiler::kSelfHitDistance / len});
  }
  return rays;
}

inline std::vector<Ray> random_rays(const std::vector<Triangle>& tris, std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const model::Bounds b = triangle_bounds(tris);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    model::Vec3 o, d;
    for (int a = 0; a < 3; ++a) o[a] = b.min[a] + u01(rng) * (b.max[a] - b.min[a]);
    do {
      d = {g(rng), g(rng), g(rng)};
    } while (glm::length(d) < 1e-6);
    rays.push_back({o, glm::normalize(d), 0.0, INFINITY});
  }
  return rays;
}

}  // namespace walk::bench
