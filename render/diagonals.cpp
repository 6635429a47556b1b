#include "render/diagonals.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace walk::render {
namespace {

// (a, b, c) rotated so that it starts at `first`; false when `first` is not a corner.
bool rotate_to(std::array<std::uint32_t, 3>& t, std::uint32_t first) {
  for (int k = 0; k < 3; ++k) {
    if (t[0] == first) return true;
    std::rotate(t.begin(), t.begin() + 1, t.end());
  }
  return false;
}

// Both diagonals split the quad into two triangles facing the same way as the first: strictly convex.
bool convex(std::span<const model::VertexRecord> vertices, std::array<std::uint32_t, 4> v) {
  for (std::uint32_t k : v)
    if (k >= vertices.size()) return false;
  auto at = [&](int k) {
    const float* p = vertices[v[std::size_t(k)]].position;
    return glm::dvec3(p[0], p[1], p[2]);
  };
  const glm::dvec3 a = at(0), b = at(1), c = at(2), d = at(3);
  const glm::dvec3 n = glm::cross(b - a, d - a);
  return glm::dot(glm::cross(b - a, c - a), n) > 0.0 && glm::dot(glm::cross(c - a, d - a), n) > 0.0 &&
         glm::dot(glm::cross(c - b, d - b), n) > 0.0;
}

float difference(const glm::vec3& a, const glm::vec3& b) {
  return std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z);
}

// Appends polygon `id`'s quads.
void append_quads(std::uint32_t id, const model::PolygonRecord& p, std::span<const std::uint32_t> indices,
                  std::span<const model::VertexRecord> vertices, std::vector<Quad>& quads) {
  const std::uint64_t end = std::uint64_t(p.first_index) + p.index_count;
  if (end > indices.size()) return;
  for (std::uint64_t i = p.first_index; i + 6 <= end;) {
    std::array<std::uint32_t, 3> t1{indices[i], indices[i + 1], indices[i + 2]};
    std::array<std::uint32_t, 3> t2{indices[i + 3], indices[i + 4], indices[i + 5]};
    // The corner of t1 not in t2.
    int alone = -1, shared = 0;
    for (int k = 0; k < 3; ++k) {
      const bool in2 = std::find(t2.begin(), t2.end(), t1[k]) != t2.end();
      shared += in2;
      if (!in2) alone = k;
    }
    if (shared != 2 || alone < 0) {
      i += 3;  // not a pair: try from the next triangle
      continue;
    }
    rotate_to(t1, t1[std::size_t(alone)]);  // t1 = (u1, p, q), counter-clockwise
    const std::uint32_t u1 = t1[0], pp = t1[1], q = t1[2];
    // t2 must run p -> u2 -> q, the shared edge reversed: then u1, p, u2, q is the quad, counter-clockwise.
    if (!rotate_to(t2, pp) || t2[2] != q) {
      i += 3;
      continue;
    }
    if (!vertices.empty() && !convex(vertices, {u1, pp, t2[1], q})) {
      i += 6;  // a real pair, but flipping it would fold: leave both triangles as they are
      continue;
    }
    quads.push_back({std::uint32_t(i), id, {u1, pp, t2[1], q}});
    i += 6;
  }
}

}  // namespace

std::vector<Quad> find_quads(std::span<const model::PolygonRecord> polygons,
                             std::span<const std::uint32_t> indices,
                             std::span<const model::VertexRecord> vertices) {
  std::vector<Quad> quads;
  for (std::uint32_t id = 0; id < polygons.size(); ++id)
    append_quads(id, polygons[id], indices, vertices, quads);
  return quads;
}

std::vector<Quad> find_quads(std::span<const model::PolygonRecord> polygons,
                             std::span<const std::uint32_t> ids, std::span<const std::uint32_t> indices,
                             std::span<const model::VertexRecord> vertices) {
  std::vector<Quad> quads;
  for (const std::uint32_t id : ids)
    if (id < polygons.size()) append_quads(id, polygons[id], indices, vertices, quads);
  return quads;
}

std::size_t choose_diagonals(std::span<const Quad> quads, std::span<const glm::vec3> colour,
                             std::span<std::uint32_t> indices) {
  std::size_t flipped = 0;
  for (const Quad& quad : quads) {
    const auto& v = quad.v;
    if (std::max({v[0], v[1], v[2], v[3]}) >= colour.size() || quad.first_index + 6 > indices.size())
      continue;
    const bool other = difference(colour[v[0]], colour[v[2]]) < difference(colour[v[1]], colour[v[3]]);
    const std::array<std::uint32_t, 6> tris =
        other ? std::array<std::uint32_t, 6>{v[0], v[1], v[2], v[0], v[2], v[3]}
              : std::array<std::uint32_t, 6>{v[0], v[1], v[3], v[1], v[2], v[3]};
    std::copy(tris.begin(), tris.end(), indices.begin() + quad.first_index);
    flipped += other;
  }
  return flipped;
}

}  // namespace walk::render
