#include "render/frustum.hpp"

#include <algorithm>
#include <limits>

namespace walk::render {

std::vector<Box> polygon_boxes(std::span<const model::PolygonRecord> polygons,
                               std::span<const model::VertexRecord> vertices) {
  constexpr float kBig = std::numeric_limits<float>::max();
  std::vector<Box> boxes(polygons.size(), Box{{kBig, kBig, kBig}, {-kBig, -kBig, -kBig}});
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    const auto& poly = polygons[p];
    for (std::uint64_t v = poly.first_vertex; v < std::uint64_t(poly.first_vertex) + poly.vertex_count; ++v) {
      if (v >= vertices.size()) break;
      for (int k = 0; k < 3; ++k) {
        boxes[p].lo[k] = std::min(boxes[p].lo[k], vertices[v].position[k]);
        boxes[p].hi[k] = std::max(boxes[p].hi[k], vertices[v].position[k]);
      }
    }
  }
  return boxes;
}

std::vector<std::uint32_t> in_frustum(const glm::mat4& m, std::span<const Box> boxes,
                                      std::span<const std::uint32_t> candidates) {
  // Rows of the matrix (glm is column-major: m[column][row]); plane = row3 +/- row i.
  auto row = [&](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  const glm::vec4 planes[6] = {row(3) + row(0), row(3) - row(0), row(3) + row(1),
                               row(3) - row(1), row(3) + row(2), row(3) - row(2)};
  std::vector<std::uint32_t> out;
  out.reserve(candidates.size());
  for (std::uint32_t id : candidates) {
    if (id >= boxes.size()) continue;
    const Box& b = boxes[id];
    if (b.lo[0] > b.hi[0]) continue;
    bool inside = true;
    for (const glm::vec4& p : planes) {
      // The box corner furthest along the plane's normal: if even it is behind, the whole box is.
      const float x = p.x >= 0.0f ? b.hi[0] : b.lo[0];
      const float y = p.y >= 0.0f ? b.hi[1] : b.lo[1];
      const float z = p.z >= 0.0f ? b.hi[2] : b.lo[2];
      if (p.x * x + p.y * y + p.z * z + p.w < 0.0f) {
        inside = false;
        break;
      }
    }
    if (inside) out.push_back(id);
  }
  return out;
}

}  // namespace walk::render
