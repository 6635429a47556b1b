#pragma once
// Single-occluder culling inside cells (after Airey's shadow volumes): a polygon that lies wholly in the
// umbra of one convex opaque polygon, as seen from the portal every sight line into its cell crosses, is
// hidden along that portal sequence. The portal flow models only what covers the cells' faces; walls
// standing inside a cell (a diagonal wall across a corner, a wall a fraction of a degree off an axis, which
// the axial partition cannot split along) hide what lies behind them only through this test.
#include <cstdint>
#include <optional>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/partition/partition.hpp"

namespace walk::compiler {

struct Occluder {
  Winding outline;           // convex, counter-clockwise about plane.n
  Plane plane;               // through the outline; n is the polygon's front normal
  std::vector<Plane> edges;  // per outline edge: unit normal in the plane, pointing inside
  double area = 0.0;
};

// The occluder with this outline (convex, counter-clockwise about the unit `normal`); none when the outline
// has fewer than three points or an edge of no length (nothing lies strictly inside it).
[[nodiscard]] std::optional<Occluder> make_occluder(Winding outline, const model::Vec3& normal);

// Occluders smaller than this (m^2) rarely hide a whole polygon or portal; leaving them out keeps the test
// cheap (a door leaf is about 2 m^2).
inline constexpr double kMinOccluderArea = 0.5;
// At most this many occluders per cell, the largest first.
inline constexpr std::size_t kMaxOccludersPerCell = 8;

// The opaque polygons of each cell that can occlude: convex (the polygon fills its hull), planar, at least
// kMinOccluderArea; the largest kMaxOccludersPerCell of each cell.
[[nodiscard]] std::vector<std::vector<Occluder>> cell_occluders(const Partition& part,
                                                                const std::vector<VisPolygon>& polygons);

// Does every segment from a point of `light` to a point of `target` (both convex) pass through the inside
// of `o`, by at least kPlaneEpsilon? Then nothing of `target` is seen through `light`. With
// `cull_back_faces` the occluder blocks only sight lines meeting its front, so `light` must lie in front of
// it. Exact for convex windings: the segments between their vertices are enough (the crossings of all other
// segments lie in the convex hull of those).
[[nodiscard]] bool hidden_by(const Winding& target, const Winding& light, const Occluder& o,
                             bool cull_back_faces);

}  // namespace walk::compiler
