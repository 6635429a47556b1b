#pragma once
// Shared by the ray-casting tests: compare one caster's answers with a reference caster's on the same rays.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler::testing {

// Two hits on different polygons this close along the ray (in metres) are a documented tie: coincident
// polygons (back-to-back zone walls, windows overlaid on walls) or a ray through a shared edge.
inline constexpr double kTieCheck = 1e-7;

// A hit this close to an edge of its triangle (metres) is an edge case: the ray passes through the edge
// within rounding, and a reference that rounds differently may see it pass on the other side (grazing rays
// along a wall that meet the floor's edge, say). Such disagreements are counted apart, not failed.
inline constexpr double kEdgeCheck = 1e-7;

// A direction uniform on the unit sphere.
inline model::Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  model::Vec3 d;
  do d = {g(rng), g(rng), g(rng)};
  while (glm::length(d) < 1e-3);
  return glm::normalize(d);
}

// An n x n grid of square tiles of side `size` in the plane z = `z` from the origin, two triangles per tile;
// tile (i, j) is polygon i * n + j.
inline std::vector<Triangle> tiled_plane(int n, double size, double z) {
  std::vector<Triangle> tiles;
  std::uint32_t p = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j, ++p) {
      const double x = i * size, y = j * size;
      tiles.push_back({{x, y, z}, {x + size, y, z}, {x + size, y + size, z}, p});
      tiles.push_back({{x, y, z}, {x + size, y + size, z}, {x, y + size, z}, p});
    }
  return tiles;
}

struct Agreement {
  std::size_t rays = 0, hits = 0, same = 0, ties = 0, edge_cases = 0, closest_mismatch = 0, any_mismatch = 0;
  std::size_t reference_wrong = 0;  // disagreements where brute force sided with ours
  std::string first_problem;
};

inline double segment_distance(const model::Vec3& p, const model::Vec3& a, const model::Vec3& b) {
  const model::Vec3 ab = b - a;
  const double len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
  const double s = len2 > 0.0
                       ? std::clamp(((p - a).x * ab.x + (p - a).y * ab.y + (p - a).z * ab.z) / len2, 0.0, 1.0)
                       : 0.0;
  const model::Vec3 q = a + s * ab - p;
  return std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
}

// A ray meeting a surface at a sine below this is grazing: a rounding of 1e-10 m across the surface moves
// the hit 1e-6 m along the ray (occlusion rays between two points of one wall lie in its plane).
inline constexpr double kGrazing = 1e-4;

// Is the answer `h` ill-conditioned: its hit point within kEdgeCheck of an edge of its polygon (of any
// triangle of it: the axial planes report a rectangle merged from two triangles by one of them), or the ray
// grazing the triangle? Casters that round differently may then disagree, and both are right.
inline bool near_edge(std::span<const Triangle> tris, const Ray& r, const RayHit& h) {
  if (!h.hit()) return false;
  const Triangle& t = tris[h.triangle];
  const model::Vec3 p = r.origin + h.t * r.dir;
  const model::Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const model::Vec3 n(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
  const double nn = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  const double dd = std::sqrt(r.dir.x * r.dir.x + r.dir.y * r.dir.y + r.dir.z * r.dir.z);
  if (std::abs(n.x * r.dir.x + n.y * r.dir.y + n.z * r.dir.z) <= kGrazing * nn * dd) return true;
  // Triangles of one polygon are consecutive in every model here; look 64 either side.
  const std::size_t lo = h.triangle >= 64 ? h.triangle - 64 : 0,
                    hi = std::min(tris.size(), std::size_t{h.triangle} + 65);
  for (std::size_t i = lo; i < hi; ++i) {
    const Triangle& q = tris[i];
    if (q.polygon != t.polygon) continue;
    if (std::min({segment_distance(p, q.a, q.b), segment_distance(p, q.b, q.c),
                  segment_distance(p, q.c, q.a)}) <= kEdgeCheck)
      return true;
  }
  return false;
}

// Same polygon (or a tie) at the same distance?
inline bool same_answer(const Ray& r, const RayHit& a, const RayHit& b) {
  if (a.hit() != b.hit()) return false;
  if (!a.hit()) return true;
  const double len = std::sqrt(r.dir.x * r.dir.x + r.dir.y * r.dir.y + r.dir.z * r.dir.z);
  return std::abs(a.t - b.t) * len <= kTieCheck * std::max(1.0, b.t * len);
}

// `judge` (brute force), when given, settles each disagreement: where it agrees with ours, the reference
// was wrong (the BVH's Möller-Trumbore test is not watertight and skips thin triangles).
inline Agreement compare_casters(const RayCaster& ours, const RayCaster& ref, std::span<const Triangle> tris,
                                 std::span<const Ray> rays, unsigned threads = 2,
                                 const RayCaster* judge = nullptr) {
  std::vector<RayHit> a(rays.size()), b(rays.size());
  std::vector<std::uint8_t> oa(rays.size()), ob(rays.size());
  ours.closest_batch(rays, a, threads);
  ref.closest_batch(rays, b, threads);
  ours.occluded_batch(rays, oa, threads);
  ref.occluded_batch(rays, ob, threads);
  Agreement g;
  g.rays = rays.size();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double len = std::sqrt(rays[i].dir.x * rays[i].dir.x + rays[i].dir.y * rays[i].dir.y +
                                 rays[i].dir.z * rays[i].dir.z);
    const bool agree_hit = a[i].hit() == b[i].hit();
    if (b[i].hit()) ++g.hits;
    if (agree_hit &&
        (!a[i].hit() || (a[i].polygon == b[i].polygon &&
                         std::abs(a[i].t - b[i].t) * len <= kTieCheck * std::max(1.0, b[i].t * len)))) {
      ++g.same;
    } else if (a[i].hit() && b[i].hit() &&
               std::abs(a[i].t - b[i].t) * len <= kTieCheck * std::max(1.0, b[i].t * len)) {
      ++g.ties;
    } else if (near_edge(tris, rays[i], a[i]) || near_edge(tris, rays[i], b[i])) {
      ++g.edge_cases;
    } else if (judge && same_answer(rays[i], a[i], judge->closest(rays[i]))) {
      ++g.reference_wrong;
    } else {
      if (g.first_problem.empty())
        g.first_problem = "ray " + std::to_string(i) + ": " + std::string(ours.name()) + " polygon " +
                          std::to_string(a[i].polygon) + " t " + std::to_string(a[i].t) + ", " +
                          std::string(ref.name()) + " polygon " + std::to_string(b[i].polygon) + " t " +
                          std::to_string(b[i].t);
      ++g.closest_mismatch;
    }
    if (oa[i] != ob[i] && !near_edge(tris, rays[i], a[i]) && !near_edge(tris, rays[i], b[i])) {
      if (judge && judge->occluded(rays[i]) == (oa[i] != 0))
        ++g.reference_wrong;
      else
        ++g.any_mismatch;
    }
    // Any-hit must agree with closest-hit within one caster.
    if (oa[i] != (a[i].hit() ? 1 : 0)) ++g.any_mismatch;
  }
  return g;
}

}  // namespace walk::compiler::testing
