#pragma once
// Quad diagonals chosen by colour (the paper's third refinement step): the compiler dices each polygon into
// quads of two triangles; which diagonal splits a quad decides how Gouraud shading stretches its corners'
// light. Under the current dimmer mix, each quad is split along the diagonal whose ends differ least in
// colour, so shading follows the light's contours instead of the dicing direction. Pure CPU.
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"

namespace walk::render {

// Two consecutive triangles of one polygon sharing an edge: corners counter-clockwise, v[0]..v[3], split
// in the bundle along v[1]-v[3]; `first_index` is where the pair's six indices start in INDX.
struct Quad {
  std::uint32_t first_index = 0;
  std::uint32_t polygon = 0;
  std::array<std::uint32_t, 4> v{};
};

// With `vertices`, pairs whose union is not strictly convex are skipped: flipping their diagonal would fold a
// triangle over the other.
[[nodiscard]] std::vector<Quad> find_quads(std::span<const model::PolygonRecord> polygons,
                                           std::span<const std::uint32_t> indices,
                                           std::span<const model::VertexRecord> vertices = {});
// The quads of the polygons `ids` only, in that order (a still view's units, found when first seen).
[[nodiscard]] std::vector<Quad> find_quads(std::span<const model::PolygonRecord> polygons,
                                           std::span<const std::uint32_t> ids,
                                           std::span<const std::uint32_t> indices,
                                           std::span<const model::VertexRecord> vertices);

// Rewrites each quad's six entries of `indices` (same layout as INDX, so draw lists stay valid) for the
// diagonal with the smaller colour difference between its ends; ties keep the bundle's. Returns how many
// quads are split differently from the bundle.
std::size_t choose_diagonals(std::span<const Quad> quads, std::span<const glm::vec3> colour,
                             std::span<std::uint32_t> indices);

}  // namespace walk::render
