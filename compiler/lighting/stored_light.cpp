#include "compiler/lighting/stored_light.hpp"

#include <cmath>
#include <glm/geometric.hpp>

#include "compiler/geometry/triangle_weights.hpp"

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
  const auto w = triangle_weights(t.a, t.b, t.c, origin + dir * hit->t);
  out.assign(bundle_.circuits().size() * 3, 0.0);
  const auto light = bundle_.light();
  for (int i = 0; i < 3 && !light.empty(); ++i)
    for (const model::LightEntry& e : light.row(c[i]))
      for (int j = 0; j < 3; ++j) out[e.circuit * 3 + j] += w[i] * e.rgb[j];
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
