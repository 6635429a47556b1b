#pragma once
// Airey's model-space subdivision: candidate axial splitting planes taken from the model's axial polygons,
// (structure only: VisPolygon::detail items are neither candidates nor counted) each scored by partition
// priority = w_o*occlusion + w_b*balance + w_s*split (each 0..1), recursing on the
// best plane until none scores above the threshold (or is at least half wall with room on both sides:
// kDividingWall in partition.cpp) or the depth limit is reached. Leaves are cells.
#include <cstdint>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/partition/visibility_config.hpp"
#include "model/bundle_format.hpp"

namespace walk::compiler {

// The opaque polygons lying in one axial plane: what covers that plane, for occlusion and portals.
struct AxialPlane {
  int axis = 0;
  double coord = 0.0;
  std::vector<std::uint32_t> opaque;  // polygon ids
  std::vector<std::uint32_t> glass;
};

struct PlaneScore {
  double occlusion = 0.0;  // fraction of the cell's cross-section covered by opaque polygons in the plane
  double balance = 0.0;    // 1 - |front - back| / (front + back) structure polygons
  double split = 0.0;      // 1 - split structure polygons / structure polygons in the cell
  double priority = 0.0;
};

struct Partition {
  Box bounds;
  std::vector<model::NodeRecord> nodes;  // preorder: children after parents; empty for a single cell
  std::vector<Box> cells;
  std::vector<std::vector<std::uint32_t>> cell_polygons;  // drawn polygons overlapping each cell
  std::vector<AxialPlane> planes;                         // sorted by (axis, coord)
  int depth = 0;
  std::size_t candidates = 0;  // distinct axial planes considered
};

// Groups the axial polygons by plane (coordinates within kInPlaneTolerance merge).
[[nodiscard]] std::vector<AxialPlane> axial_planes(const std::vector<VisPolygon>& polygons);
// The plane of `planes` at (axis, coord), or nullptr.
[[nodiscard]] const AxialPlane* find_plane(const std::vector<AxialPlane>& planes, int axis, double coord);

// Fraction of the rectangle `cell` cut by the plane (axis, coord) that `plane`'s opaque polygons cover.
[[nodiscard]] double occlusion_fraction(const AxialPlane& plane, const Box& cell,
                                        const std::vector<VisPolygon>& polygons);

[[nodiscard]] PlaneScore score_plane(const AxialPlane& plane, const Box& cell,
                                     const std::vector<std::uint32_t>& cell_polygons,
                                     const std::vector<VisPolygon>& polygons, const VisibilityConfig& config,
                                     double needed = -1.0);

[[nodiscard]] Partition build_partition(const std::vector<VisPolygon>& polygons,
                                        const VisibilityConfig& config);

// (score_plane leaves occlusion at 0 when even full occlusion could not reach `needed`.)
// Cell index of a point by walking the node tree (the same rule as model::Bundle::locate_cell).
[[nodiscard]] std::uint32_t locate(const std::vector<model::NodeRecord>& nodes, const model::Vec3& p);

}  // namespace walk::compiler
