#pragma once
// The skeleton's TriangleBvh (Möller-Trumbore, not watertight) behind the RayCaster interface, for
// comparison.
#include "compiler/raycast/local_triangles.hpp"

namespace walk::compiler {

class BvhCaster final : public RayCaster {
 public:
  explicit BvhCaster(std::span<const Triangle> triangles);
  [[nodiscard]] std::string_view name() const override { return "bvh"; }
  [[nodiscard]] RayHit closest(const Ray& ray) const override;
  [[nodiscard]] bool occluded(const Ray& ray) const override;
  [[nodiscard]] std::size_t memory_bytes() const override;

 private:
  model::Vec3 centre_;
  TriangleBvh bvh_;  // holds local triangles, reordered; Triangle::polygon keeps the caller's triangle index
  std::vector<std::uint32_t> polygon_;  // caller's polygon id per caller triangle index
  std::vector<model::Vec3> normals_;    // per caller triangle index
};

}  // namespace walk::compiler
