#include "compiler/import/uv_fit.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace walk::compiler {
namespace {

// Below this, the corners' spread in the plane (the normal matrix's determinant, divided by the cube of its
// trace so that it does not depend on the polygon's size or corner count) is taken for a line: 1e-12 is far
// above double rounding of the sums and far below any polygon clean-up keeps (its slivers are ~1e-6 thick).
constexpr double kMinRelativeSpread = 1e-12;

}  // namespace

std::optional<model::TextureMap> fit_texture_map(std::span<const model::Vec3> corners,
                                                 std::span<const glm::dvec2> uvs) {
  if (corners.size() < 3 || uvs.size() != corners.size()) return std::nullopt;
  const std::vector<model::Vec3> loop(corners.begin(), corners.end());
  const model::Vec3 area = model::area_vector(loop);
  const double twice_area = glm::length(area);
  if (!(twice_area > 0.0)) return std::nullopt;
  const model::Vec3 normal = area / twice_area;
  // A frame in the plane, relative to the first corner (precision for models far from the origin).
  const model::Vec3 origin = corners[0];
  model::Vec3 a(0.0);
  for (std::size_t i = 1; i < corners.size() && glm::length(a) == 0.0; ++i) {
    const model::Vec3 d = corners[i] - origin;
    a = d - normal * glm::dot(d, normal);
  }
  if (!(glm::length(a) > 0.0)) return std::nullopt;
  a = glm::normalize(a);
  const model::Vec3 b = glm::cross(normal, a);
  // Normal equations of u ~ alpha x + beta y + gamma over the corners (likewise v); glm is column-major.
  glm::dmat3 m(0.0);
  glm::dvec3 ru(0.0), rv(0.0);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const model::Vec3 d = corners[i] - origin;
    const glm::dvec3 row(glm::dot(d, a), glm::dot(d, b), 1.0);
    m += glm::outerProduct(row, row);
    ru += row * uvs[i].x;
    rv += row * uvs[i].y;
  }
  const double trace = m[0][0] + m[1][1] + m[2][2];
  const double det = glm::determinant(m);
  if (!(std::abs(det) > kMinRelativeSpread * trace * trace * trace)) return std::nullopt;
  const glm::dmat3 inverse = glm::inverse(m);
  const glm::dvec3 cu = inverse * ru, cv = inverse * rv;
  if (!std::isfinite(cu.x + cu.y + cu.z + cv.x + cv.y + cv.z)) return std::nullopt;
  model::TextureMap map;
  map.u_gradient = cu.x * a + cu.y * b;
  map.v_gradient = cv.x * a + cv.y * b;
  // u(p) = gradient . (p - origin) + gamma, less whole repeats of the first corner's value.
  map.u_offset = cu.z - std::floor(cu.z) - glm::dot(map.u_gradient, origin);
  map.v_offset = cv.z - std::floor(cv.z) - glm::dot(map.v_gradient, origin);
  return map;
}

}  // namespace walk::compiler
