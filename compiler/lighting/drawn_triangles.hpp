#pragma once
// The surfaces a bundle draws and lights (its opaque and glass polygons; panels are light, not surfaces)
// as triangles with their three VERT ids, in index order: what the probe and the path-traced reference
// trace against and read the stored light at.
#include <array>
#include <cstdint>
#include <vector>

#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::compiler {

using TriangleCorners = std::array<std::uint32_t, 3>;

// `with_panels`: area luminaires' panels too (surfaces that reflect and block light like the rest; the
// radiosity solver treats them so).
[[nodiscard]] std::vector<TriangleCorners> drawn_triangles(const model::Bundle& bundle,
                                                           bool with_panels = false);

[[nodiscard]] inline model::Vec3 vertex_position(const model::VertexRecord& v) {
  return {v.position[0], v.position[1], v.position[2]};
}

// The side the display shows, as the bundle stores it (not normalised).
[[nodiscard]] inline model::Vec3 vertex_normal(const model::VertexRecord& v) {
  return {v.normal[0], v.normal[1], v.normal[2]};
}

}  // namespace walk::compiler
