#pragma once
// Triangles moved to a whole-metre local frame, with the facing normal each backend needs for the tie rule.
#include <span>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

struct LocalTriangles {
  model::Vec3 centre{0.0};
  std::vector<Triangle> triangles;   // vertices minus centre, same order and ids as the input
  std::vector<model::Vec3> normals;  // cross(b - a, c - a): front side is where it points

  explicit LocalTriangles(std::span<const Triangle> input);
  [[nodiscard]] bool front(std::uint32_t i, const model::Vec3& dir) const;
  [[nodiscard]] std::size_t memory_bytes() const;
};

// Tie rule shared by the backends: is a hit at (t, front, triangle) better than `best`? `tie` is
// kTieDistance in units of the ray's t.
[[nodiscard]] inline bool better_hit(double t, bool front, std::uint32_t triangle, const RayHit& best,
                                     double tie) {
  if (!best.hit() || t < best.t - tie) return true;
  if (t > best.t + tie) return false;
  if (front != best.front) return front;
  return triangle < best.triangle;
}

}  // namespace walk::compiler
