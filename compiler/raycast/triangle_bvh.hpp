#pragma once
// A plain bounding-volume hierarchy over triangles, in double precision: the skeleton's ray caster for
// shadow rays and the reference the paper's axial plane structure (issue 4) is measured against.
#include <cstdint>
#include <optional>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct Triangle {
  model::Vec3 a, b, c;
  std::uint32_t polygon = 0;
};

struct Hit {
  double t = 0.0;
  std::uint32_t triangle = 0;
};

class TriangleBvh {
 public:
  explicit TriangleBvh(std::vector<Triangle> triangles);

  // Closest hit with t in (t_min, t_max); dir need not be unit length (t is in units of dir).
  [[nodiscard]] std::optional<Hit> closest(const model::Vec3& origin, const model::Vec3& dir, double t_min,
                                           double t_max) const;
  // Closest hit, but among hits within `tie` of each other the one facing the ray (dot(dir, normal) < 0)
  // wins. Buildings drawn per room hold every shared wall twice, back to back with opposite normals; this
  // makes a ray from either room land on its own room's copy.
  [[nodiscard]] std::optional<Hit> closest_facing(const model::Vec3& origin, const model::Vec3& dir,
                                                  double t_min, double t_max, double tie) const;
  // Any hit with t in (t_min, t_max): the occlusion query of shadow rays.
  [[nodiscard]] bool occluded(const model::Vec3& origin, const model::Vec3& dir, double t_min,
                              double t_max) const;

  [[nodiscard]] const std::vector<Triangle>& triangles() const { return triangles_; }

 private:
  struct Node {
    model::Vec3 lo, hi;
    std::uint32_t first = 0;  // leaf: first triangle; inner: index of the right child (left is next)
    std::uint32_t count = 0;  // triangles in a leaf, 0 for an inner node
  };
  std::uint32_t build(std::uint32_t first, std::uint32_t count, int depth);
  enum class Query { kClosest, kAny, kClosestFacing };
  template <Query kQuery>
  std::optional<Hit> traverse(const model::Vec3& origin, const model::Vec3& dir, double t_min, double t_max,
                              double tie = 0.0) const;

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

// Möller–Trumbore, double precision; returns t when the ray hits the triangle's interior or edges.
[[nodiscard]] std::optional<double> intersect_triangle(const Triangle& tri, const model::Vec3& origin,
                                                       const model::Vec3& dir);

}  // namespace walk::compiler
