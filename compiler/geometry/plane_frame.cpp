#include "compiler/geometry/plane_frame.hpp"

#include <glm/geometric.hpp>

#include "compiler/geometry/mesher.hpp"

namespace walk::compiler {

glm::dvec2 PlaneFrame::to_2d(const model::Vec3& p) const {
  const model::Vec3 d = p - origin;
  return {glm::dot(d, u), glm::dot(d, v)};
}

double PlaneFrame::distance(const model::Vec3& p) const {
  return glm::dot(p - origin, normal);
}

bool plane_frame(const std::vector<model::Vec3>& vertices, PlaneFrame& out) {
  const model::Vec3 normal = polygon_normal(vertices);
  if (glm::dot(normal, normal) == 0.0) return false;
  model::Vec3 longest{0.0};
  double longest_length = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    model::Vec3 edge = vertices[(i + 1) % vertices.size()] - vertices[i];
    edge -= normal * glm::dot(edge, normal);  // in-plane part (the polygon may be slightly non-planar)
    const double length = glm::length(edge);
    if (length > longest_length) {
      longest_length = length;
      longest = edge / length;
    }
  }
  if (longest_length == 0.0) return false;
  out.origin = vertices.front();
  out.normal = normal;
  out.u = longest;
  out.v = glm::cross(normal, longest);
  return true;
}

}  // namespace walk::compiler
