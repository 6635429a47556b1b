#include "render/subdivision.hpp"

#include <algorithm>
#include <cmath>

namespace walk::render {
namespace {

float difference(const glm::vec3& a, const glm::vec3& b) {
  return std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z);
}

struct Corner {
  glm::vec3 p, c;
};

Corner lerp(const Corner& a, const Corner& b, float t) {
  return {a.p + (b.p - a.p) * t, a.c + (b.c - a.c) * t};
}

void emit(const Corner q[4], std::uint32_t polygon, float threshold, int depth,
          std::vector<ShadedVertex>& out) {
  const glm::vec3 c[4] = {q[0].c, q[1].c, q[2].c, q[3].c};
  if (depth <= 0 || quad_twist(c) <= threshold) {
    // Leaf: two triangles, split along the diagonal of least colour difference (as the parent step does).
    const bool other = difference(c[0], c[2]) < difference(c[1], c[3]);
    const int order[6] = {0, 1, 2, 0, 2, 3};
    const int bundle_order[6] = {0, 1, 3, 1, 2, 3};
    for (int k : other ? order : bundle_order) out.push_back({q[k].p, q[k].c, polygon});
    return;
  }
  // Bilinear: edge midpoints and the centre (the mean of the corners) lie on the bilinear surface.
  const Corner m01 = lerp(q[0], q[1], 0.5f), m12 = lerp(q[1], q[2], 0.5f), m23 = lerp(q[2], q[3], 0.5f),
               m30 = lerp(q[3], q[0], 0.5f), centre = lerp(m01, m23, 0.5f);
  const Corner children[4][4] = {
      {q[0], m01, centre, m30}, {m01, q[1], m12, centre}, {centre, m12, q[2], m23}, {m30, centre, m23, q[3]}};
  for (const auto& child : children) emit(child, polygon, threshold, depth - 1, out);
}

}  // namespace

float quad_twist(const glm::vec3 c[4]) {
  const glm::vec3 t = (c[0] - c[1] + c[2] - c[3]) * 0.25f;
  return std::max({std::abs(t.x), std::abs(t.y), std::abs(t.z)});
}

Subdivision subdivide(std::span<const Quad> quads, std::span<const model::VertexRecord> vertices,
                      std::span<const glm::vec3> radiosity, float threshold, int max_depth) {
  Subdivision result;
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const auto& v = quads[i].v;
    if (std::max({v[0], v[1], v[2], v[3]}) >= std::min(vertices.size(), radiosity.size())) continue;
    const glm::vec3 c[4] = {radiosity[v[0]], radiosity[v[1]], radiosity[v[2]], radiosity[v[3]]};
    if (max_depth <= 0 || quad_twist(c) <= threshold) continue;
    Corner q[4];
    for (int k = 0; k < 4; ++k) {
      const float* p = vertices[v[k]].position;
      q[k] = {{p[0], p[1], p[2]}, c[k]};
    }
    emit(q, quads[i].polygon, threshold, max_depth, result.triangles);
    result.replaced_quads.push_back(i);
  }
  return result;
}

}  // namespace walk::render
