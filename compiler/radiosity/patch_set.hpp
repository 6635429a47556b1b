#pragma once
// Patches for radiosity: the triangles of each polygon's diced mesh, sharing vertices, each keeping its
// parent polygon. Patch size is the mesher's grid (the paper diced into 21 square-inch patches).
#include <array>
#include <cstdint>
#include <vector>

#include "compiler/raycast/triangle_bvh.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct Patch {
  std::array<std::uint32_t, 3> v{};  // counter-clockwise about `normal`
  model::Vec3 normal{0.0, 0.0, 1.0};
  double area = 0.0;
  model::Rgb reflectance{0.5};
  std::uint32_t polygon = 0;
};

struct PatchSet {
  std::vector<model::Vec3> vertices;
  std::vector<Patch> patches;

  // Adds one triangle; returns false (and adds nothing) for a degenerate one.
  bool add(std::uint32_t a, std::uint32_t b, std::uint32_t c, const model::Rgb& reflectance,
           std::uint32_t polygon);
  // The patches as triangles for a ray caster, each carrying its patch's index (as `polygon`).
  [[nodiscard]] std::vector<Triangle> triangles() const;
};

}  // namespace walk::compiler
