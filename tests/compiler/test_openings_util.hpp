#pragma once
// Small independent geometry helpers for the geometry tests (deliberately not the code under test).
#include <cmath>
#include <glm/geometric.hpp>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler::test {

using model::Vec3;

// Area vector of a closed loop (half the Newell sum): its length is the area, its direction the normal.
inline Vec3 area_vector(const std::vector<Vec3>& loop) {
  Vec3 sum{0.0};
  if (loop.empty()) return sum;
  for (std::size_t i = 1; i + 1 < loop.size(); ++i)
    sum += glm::cross(loop[i] - loop[0], loop[i + 1] - loop[0]);
  return 0.5 * sum;
}

inline double loop_area(const std::vector<Vec3>& loop) {
  return glm::length(area_vector(loop));
}

inline double polygon_area(const model::Polygon& p) {
  double area = loop_area(p.vertices);
  for (const auto& hole : p.holes) area -= loop_area(hole);
  return area;
}

inline Vec3 centroid(const std::vector<Vec3>& loop) {
  Vec3 c{0.0};
  for (const auto& v : loop) c += v;
  return c / static_cast<double>(loop.size());
}

// Point-in-loop by crossings, in the coordinate plane that drops the normal's largest component.
inline bool inside_loop(const std::vector<Vec3>& loop, const Vec3& p, const Vec3& normal) {
  const Vec3 a = glm::abs(normal);
  const int drop = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  const int i0 = drop == 0 ? 1 : 0, i1 = drop == 2 ? 1 : 2;
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec3& u = loop[i];
    const Vec3& w = loop[j];
    if ((u[i1] > p[i1]) != (w[i1] > p[i1])) {
      const double x = (w[i0] - u[i0]) * (p[i1] - u[i1]) / (w[i1] - u[i1]) + u[i0];
      if (p[i0] < x) in = !in;
    }
  }
  return in;
}

// True when p lies on the polygon's plane (within `tolerance`) inside its outer boundary and outside its
// holes.
inline bool inside_polygon(const model::Polygon& poly, const Vec3& p, double tolerance) {
  const Vec3 n = glm::normalize(area_vector(poly.vertices));
  if (std::abs(glm::dot(p - poly.vertices[0], n)) > tolerance) return false;
  if (!inside_loop(poly.vertices, p, n)) return false;
  for (const auto& hole : poly.holes) {
    if (inside_loop(hole, p, n)) return false;
  }
  return true;
}

}  // namespace walk::compiler::test
