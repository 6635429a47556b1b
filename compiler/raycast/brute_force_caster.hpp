#pragma once
// Every triangle for every ray with the watertight test: slow, obviously right, the tests' reference.
#include "compiler/raycast/local_triangles.hpp"

namespace walk::compiler {

class BruteForceCaster final : public RayCaster {
 public:
  explicit BruteForceCaster(std::span<const Triangle> triangles) : local_(triangles) {}
  [[nodiscard]] std::string_view name() const override { return "brute"; }
  [[nodiscard]] RayHit closest(const Ray& ray) const override;
  [[nodiscard]] bool occluded(const Ray& ray) const override;
  [[nodiscard]] std::size_t memory_bytes() const override { return local_.memory_bytes(); }

 private:
  LocalTriangles local_;
};

}  // namespace walk::compiler
