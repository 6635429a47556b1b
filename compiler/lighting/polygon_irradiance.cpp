#include "compiler/lighting/polygon_irradiance.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

namespace walk::compiler {
namespace {

// An edge whose corners, seen from the point, span a cross product shorter than this (m^2) passes through
// the point (or has a corner on it): it subtends no solid angle worth counting. Far below any panel corner
// distance squared (1 mm corners: 1e-6 m^2).
constexpr double kDegenerateEdge = 1e-24;

// The part of `corners` (relative to the receiver) strictly in front of the tangent plane: a corner on it
// sees the receiver edge-on and brings nothing, so a polygon lying in the plane is left empty. (The
// visibility stages' clip keeps points near a plane, which is conservative there and wrong here.)
std::vector<model::Vec3> in_front(const std::vector<model::Vec3>& corners, const model::Vec3& normal) {
  std::vector<model::Vec3> out;
  out.reserve(corners.size() + 1);  // a convex polygon gains at most one corner
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const model::Vec3& a = corners[i];
    const model::Vec3& b = corners[(i + 1) % corners.size()];
    const double da = glm::dot(normal, a), db = glm::dot(normal, b);
    if (da > 0.0) out.push_back(a);
    if ((da > 0.0) != (db > 0.0)) out.push_back(a + (b - a) * (da / (da - db)));  // on the plane
  }
  return out;
}

}  // namespace

double projected_solid_angle(std::span<const model::Vec3> polygon, const model::Vec3& point,
                             const model::Vec3& normal) {
  if (polygon.size() < 3) return 0.0;
  std::vector<model::Vec3> relative;
  relative.reserve(polygon.size());
  for (const auto& c : polygon) relative.push_back(c - point);
  // The receiver's hemisphere: in front of the tangent plane through the point (now the origin).
  const std::vector<model::Vec3> corners = in_front(relative, normal);
  if (corners.size() < 3) return 0.0;
  // Lambert: half the sum over edges of the angle each subtends times the cosine between the receiver's
  // normal and the normal of the plane through the point and the edge. Reversing the winding flips every
  // term's sign, so the magnitude is the answer for either.
  double sum = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const model::Vec3& a = corners[i];
    const model::Vec3& b = corners[(i + 1) % corners.size()];
    const model::Vec3 c = glm::cross(a, b);
    const double length = glm::length(c);
    if (length * length <= kDegenerateEdge) continue;
    sum += std::atan2(length, glm::dot(a, b)) * glm::dot(normal, c) / length;
  }
  return std::min(0.5 * std::abs(sum), std::numbers::pi);
}

}  // namespace walk::compiler
