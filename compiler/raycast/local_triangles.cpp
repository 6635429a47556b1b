#include "compiler/raycast/local_triangles.hpp"

#include <glm/geometric.hpp>

namespace walk::compiler {

LocalTriangles::LocalTriangles(std::span<const Triangle> input) : centre(whole_metre_centre(input)) {
  triangles.reserve(input.size());
  normals.reserve(input.size());
  for (const auto& t : input) {
    triangles.push_back({t.a - centre, t.b - centre, t.c - centre, t.polygon});
    const auto& l = triangles.back();
    normals.push_back(glm::cross(l.b - l.a, l.c - l.a));
  }
}

bool LocalTriangles::front(std::uint32_t i, const model::Vec3& dir) const {
  return glm::dot(normals[i], dir) < 0.0;
}

std::size_t LocalTriangles::memory_bytes() const {
  return triangles.capacity() * sizeof(Triangle) + normals.capacity() * sizeof(model::Vec3);
}

}  // namespace walk::compiler
