#include "compiler/radiosity/sampling.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace walk::compiler {

std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b) {
  SplitMix m(a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull));
  return m.next();
}

model::Vec3 perpendicular(const model::Vec3& n) {
  // Duff et al. 2017 branchless orthonormal basis: stable for every unit n, including n = -z.
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  return {1.0 + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x};
}

model::Vec3 cosine_direction(const model::Vec3& normal, double u1, double u2) {
  const double r = std::sqrt(u1);
  const double phi = 2.0 * std::numbers::pi * u2;
  const model::Vec3 t = perpendicular(normal);
  const model::Vec3 b = glm::cross(normal, t);
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + normal * std::sqrt(std::max(0.0, 1.0 - u1));
}

model::Vec3 triangle_point(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c, double u1,
                           double u2) {
  const double s = std::sqrt(u1);
  return a * (1.0 - s) + b * (s * (1.0 - u2)) + c * (s * u2);
}

}  // namespace walk::compiler
