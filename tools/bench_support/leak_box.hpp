#pragma once
// Closed boxes for the leak test: each face a grid of quads (two triangles of one polygon) or of triangles
// (alternating diagonals and four-triangle fans, so vertices are shared by 4 to 8 triangles), optionally
// rotated off the axes and moved. Every vertex comes from one lattice point computed once, so neighbours
// share bit-identical corners; rays aim exactly at vertices or at points on edges.
#include <glm/mat3x3.hpp>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::bench {

struct LeakBox {
  std::vector<compiler::Triangle> triangles;
  std::vector<model::Vec3> vertices;                           // every mesh vertex
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // vertex pairs of every triangle edge
  glm::dmat3 rotation{1.0};
  model::Vec3 lo{-1.3, -0.7, 0.2}, hi{2.1, 1.9, 3.3}, shift{0.0};
};

// `cells` quads per face side; `rotation` applied about the origin, then `shift` added.
inline LeakBox leak_box(bool quads, int cells, const glm::dmat3& rotation = glm::dmat3(1.0),
                        const model::Vec3& shift = model::Vec3(0.0)) {
  LeakBox box;
  box.rotation = rotation;
  box.shift = shift;
  const int n = 2 * cells;  // lattice: quad corners at even coordinates, fan centres at odd
  std::map<std::tuple<int, int, int>, std::uint32_t> index;
  auto vertex = [&](int i, int j, int k) {
    const auto key = std::make_tuple(i, j, k);
    if (auto it = index.find(key); it != index.end()) return it->second;
    const int c[3] = {i, j, k};
    model::Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.lo[a] + (box.hi[a] - box.lo[a]) * c[a] / n;
    box.vertices.push_back(rotation * p + shift);
    return index[key] = static_cast<std::uint32_t>(box.vertices.size() - 1);
  };
  std::uint32_t polygon = 0;
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t poly) {
    box.triangles.push_back({box.vertices[a], box.vertices[b], box.vertices[c], poly});
    box.edges.emplace_back(a, b);
    box.edges.emplace_back(b, c);
    box.edges.emplace_back(c, a);
  };
  for (int k = 0; k < 3; ++k) {
    const int ua = (k + 1) % 3, va = (k + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      auto at = [&](int a, int b) {
        int c[3];
        c[k] = side * n;
        c[ua] = a;
        c[va] = b;
        return vertex(c[0], c[1], c[2]);
      };
      for (int a = 0; a < n; a += 2) {
        for (int b = 0; b < n; b += 2) {
          std::uint32_t q[4] = {at(a, b), at(a + 2, b), at(a + 2, b + 2), at(a, b + 2)};
          if (side == 1) std::swap(q[1], q[3]);  // fronts face the inside
          if (quads) {
            tri(q[0], q[1], q[2], polygon);
            tri(q[0], q[2], q[3], polygon);
            ++polygon;
          } else if ((a / 2 + b / 2) % 3 == 0) {
            const std::uint32_t m = at(a + 1, b + 1);
            for (int e = 0; e < 4; ++e) tri(q[e], q[(e + 1) % 4], m, polygon++);
          } else if ((a / 2 + b / 2) % 2 == 0) {
            tri(q[0], q[1], q[2], polygon++);
            tri(q[0], q[2], q[3], polygon++);
          } else {
            tri(q[0], q[1], q[3], polygon++);
            tri(q[1], q[2], q[3], polygon++);
          }
        }
      }
    }
  }
  return box;
}

// Rays from inside the box (its central 90%), half aimed exactly at a mesh vertex, half at a point on an
// edge.
inline std::vector<compiler::Ray> leak_rays(const LeakBox& box, std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick_v(0, box.vertices.size() - 1),
      pick_e(0, box.edges.size() - 1);
  std::vector<compiler::Ray> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    model::Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.lo[a] + (0.05 + 0.9 * u01(rng)) * (box.hi[a] - box.lo[a]);
    const model::Vec3 o = box.rotation * p + box.shift;
    model::Vec3 target;
    if (i % 2 == 0) {
      target = box.vertices[pick_v(rng)];
    } else {
      const auto [a, b] = box.edges[pick_e(rng)];
      const double s = u01(rng);
      target = box.vertices[a] + s * (box.vertices[b] - box.vertices[a]);
    }
    rays.push_back({o, target - o, 0.0, INFINITY});
  }
  return rays;
}

}  // namespace walk::bench
