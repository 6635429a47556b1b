#include "compiler/geometry/triangle_weights.hpp"

#include <algorithm>
#include <glm/geometric.hpp>

namespace walk::compiler {

std::array<double, 3> triangle_weights(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c,
                                       const model::Vec3& p) {
  const model::Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  // The Gram determinant is |e1 x e2|^2; exactly 0 (or rounding's negative) only when the corners are
  // collinear, and then no weight is meaningful.
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
  const double w1 = std::clamp((d22 * d1 - d12 * d2) / det, 0.0, 1.0);
  const double w2 = std::clamp((d11 * d2 - d12 * d1) / det, 0.0, 1.0 - w1);
  return {1.0 - w1 - w2, w1, w2};
}

}  // namespace walk::compiler
