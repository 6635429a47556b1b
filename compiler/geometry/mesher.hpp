#pragma once
// Turns a planar polygon with holes into triangles whose vertices also lie on a grid of `cell_size` in the
// polygon's plane, so that per-vertex lighting resolves detail at that scale. Vertices are shared within
// a polygon. Uses Clipper for the 2D booleans.
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct PolygonMesh {
  std::vector<model::Vec3> vertices;
  std::vector<std::uint32_t> triangles;  // 3 indices each, counter-clockwise about `normal`
  model::Vec3 normal{0.0, 0.0, 1.0};
};

// Grid lines closer than this (metres) to a vertex of the polygon are moved onto the vertex, so that dicing
// does not cut slivers next to edges that lie just off the grid (EnergyPlus prints 10 um steps). A
// millimetre is far below any lighting cell; cells next to such an edge grow by at most this much.
inline constexpr double kMinGridGap = 1e-3;

// cell_size <= 0 means no dicing: the fewest triangles that cover the polygon.
[[nodiscard]] PolygonMesh mesh_polygon(const model::Polygon& polygon, double cell_size);

// Newell normal of a polygon's outer boundary (unit length; zero for a degenerate polygon).
[[nodiscard]] model::Vec3 polygon_normal(const std::vector<model::Vec3>& vertices);

}  // namespace walk::compiler
