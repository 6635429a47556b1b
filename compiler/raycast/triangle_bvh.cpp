#include "compiler/raycast/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr int kMaxDepth = 48;
// Determinant below which a ray counts as parallel to a triangle; relative to |edge1|*|edge2|*|dir| ~ 1 m^2.
constexpr double kParallelEpsilon = 1e-14;

bool slab_hit(const model::Vec3& lo, const model::Vec3& hi, const model::Vec3& origin, const model::Vec3& inv,
              double t_min, double t_max) {
  for (int a = 0; a < 3; ++a) {
    double t0 = (lo[a] - origin[a]) * inv[a];
    double t1 = (hi[a] - origin[a]) * inv[a];
    if (t0 > t1) std::swap(t0, t1);
    if (std::isnan(t0)) t0 = -INFINITY;  // 0 * inf: origin on the slab with a parallel ray
    if (std::isnan(t1)) t1 = INFINITY;
    t_min = std::max(t_min, t0);
    t_max = std::min(t_max, t1);
    if (t_min > t_max) return false;
  }
  return true;
}

}  // namespace

std::optional<double> intersect_triangle(const Triangle& tri, const model::Vec3& origin,
                                         const model::Vec3& dir) {
  const model::Vec3 e1 = tri.b - tri.a;
  const model::Vec3 e2 = tri.c - tri.a;
  const model::Vec3 p = glm::cross(dir, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < kParallelEpsilon) return std::nullopt;
  const double inv = 1.0 / det;
  const model::Vec3 s = origin - tri.a;
  const double u = glm::dot(s, p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const model::Vec3 q = glm::cross(s, e1);
  const double v = glm::dot(dir, q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  return glm::dot(e2, q) * inv;
}

TriangleBvh::TriangleBvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 2);
  if (!triangles_.empty()) build(0, static_cast<std::uint32_t>(triangles_.size()), 0);
}

std::uint32_t TriangleBvh::build(std::uint32_t first, std::uint32_t count, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  model::Vec3 lo(INFINITY), hi(-INFINITY), clo(INFINITY), chi(-INFINITY);
  for (std::uint32_t i = first; i < first + count; ++i) {
    const auto& t = triangles_[i];
    lo = glm::min(lo, glm::min(t.a, glm::min(t.b, t.c)));
    hi = glm::max(hi, glm::max(t.a, glm::max(t.b, t.c)));
    const model::Vec3 centre = (t.a + t.b + t.c) / 3.0;
    clo = glm::min(clo, centre);
    chi = glm::max(chi, centre);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (count <= kLeafSize || depth >= kMaxDepth) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const model::Vec3 extent = chi - clo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t half = count / 2;
  std::nth_element(triangles_.begin() + first, triangles_.begin() + first + half,
                   triangles_.begin() + first + count, [axis](const Triangle& x, const Triangle& y) {
                     return x.a[axis] + x.b[axis] + x.c[axis] < y.a[axis] + y.b[axis] + y.c[axis];
                   });
  build(first, half, depth + 1);
  const std::uint32_t right = build(first + half, count - half, depth + 1);
  nodes_[index].first = right;
  return index;
}

namespace {
// Facing: the ray meets the triangle's front (counter-clockwise) side.
bool faces(const Triangle& t, const model::Vec3& dir) {
  return glm::dot(glm::cross(t.b - t.a, t.c - t.a), dir) < 0.0;
}
}  // namespace

template <TriangleBvh::Query kQuery>
std::optional<Hit> TriangleBvh::traverse(const model::Vec3& origin, const model::Vec3& dir, double t_min,
                                         double t_max, double tie) const {
  if (nodes_.empty()) return std::nullopt;
  const model::Vec3 inv(1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z);
  std::optional<Hit> best;
  bool best_faces = false;
  double limit = t_max;  // nodes beyond this cannot hold a better hit
  std::uint32_t stack[2 * kMaxDepth + 4];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!slab_hit(n.lo, n.hi, origin, inv, t_min, limit)) continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const auto t = intersect_triangle(triangles_[i], origin, dir);
        if (!t || *t <= t_min || *t >= t_max) continue;
        if constexpr (kQuery == Query::kAny) return Hit{*t, i};
        if constexpr (kQuery == Query::kClosest) {
          if (!best || *t < best->t) {
            best = Hit{*t, i};
            limit = *t;
          }
        } else {
          const bool f = faces(triangles_[i], dir);
          const bool better =
              !best || (*t < best->t - tie) ||
              (std::abs(*t - best->t) <= tie && ((f && !best_faces) || (f == best_faces && *t < best->t)));
          if (better) {
            best = Hit{*t, i};
            best_faces = f;
            limit = std::min(t_max, *t + tie);
          }
        }
      }
    } else {
      const auto self = static_cast<std::uint32_t>(&n - nodes_.data());
      stack[top++] = n.first;
      stack[top++] = self + 1;
    }
  }
  return best;
}

std::optional<Hit> TriangleBvh::closest(const model::Vec3& origin, const model::Vec3& dir, double t_min,
                                        double t_max) const {
  return traverse<Query::kClosest>(origin, dir, t_min, t_max);
}

std::optional<Hit> TriangleBvh::closest_facing(const model::Vec3& origin, const model::Vec3& dir,
                                               double t_min, double t_max, double tie) const {
  return traverse<Query::kClosestFacing>(origin, dir, t_min, t_max, tie);
}

bool TriangleBvh::occluded(const model::Vec3& origin, const model::Vec3& dir, double t_min,
                           double t_max) const {
  return traverse<Query::kAny>(origin, dir, t_min, t_max).has_value();
}

}  // namespace walk::compiler
