#include "compiler/lighting/stored_light.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

// Coincident back-to-back walls: hits within this (metres) go to the face looking back at the ray.
constexpr double kTieDistance = 1e-6;
// A point on a surface is read from this far in front of it (metres): above float rounding of the stored
// vertices at building scale, below any real gap between surfaces.
constexpr double kReadOffset = 1e-3;

}  // namespace

StoredLight::StoredLight(const model::Bundle& b) : bundle_(b), corners_(drawn_triangles(b)) {
  std::vector<Triangle> triangles;
  const auto v = b.vertices();
  for (std::size_t i = 0; i < corners_.size(); ++i) {
    const auto& c = corners_[i];
    triangles.push_back({vertex_position(v[c[0]]), vertex_position(v[c[1]]), vertex_position(v[c[2]]),
                         static_cast<std::uint32_t>(i)});
  }
  bvh_ = std::make_unique<TriangleBvh>(std::move(triangles));
}

bool StoredLight::along_ray(const model::Vec3& origin, const model::Vec3& dir, std::vector<double>& out,
                            bool& back, double* distance) const {
  back = false;
  const auto hit = bvh_->closest_facing(origin, dir, 0.0, 1e30, kTieDistance);
  if (!hit) return false;
  const Triangle& t = bvh_->triangles()[hit->triangle];
  const auto& c = corners_[t.polygon];
  if (glm::dot(dir, vertex_normal(bundle_.vertices()[c[0]])) >= 0.0) {
    back = true;
    return false;
  }
  if (distance) *distance = hit->t * std::sqrt(glm::dot(dir, dir));
  // Barycentric weights of the hit point in the triangle.
  const model::Vec3 p = origin + dir * hit->t;
  const model::Vec3 e1 = t.b - t.a, e2 = t.c - t.a, d = p - t.a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  double w1 = det > 0.0 ? (d22 * d1 - d12 * d2) / det : 1.0 / 3.0;
  double w2 = det > 0.0 ? (d11 * d2 - d12 * d1) / det : 1.0 / 3.0;
  w1 = std::clamp(w1, 0.0, 1.0);
  w2 = std::clamp(w2, 0.0, 1.0 - w1);
  const double w[3] = {1.0 - w1 - w2, w1, w2};
  const std::size_t k = bundle_.circuits().size() * 3;
  out.assign(k, 0.0);
  for (int i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < k; ++j) out[j] += w[i] * bundle_.light()[c[i] * k + j];
  return true;
}

model::Rgb StoredLight::on_surface(const model::Vec3& position, const model::Vec3& normal) const {
  std::vector<double> light;
  bool back = false;
  model::Rgb sum(0.0);
  if (!along_ray(position + normal * kReadOffset, -normal, light, back)) return sum;
  for (std::size_t j = 0; j < light.size(); ++j) sum[j % 3] += light[j];
  return sum;
}

}  // namespace walk::compiler
