#pragma once
// A second opinion on leaks where cells cannot follow the walls. The inside flood (inside_flood.hpp) passes
// from cell to cell through the open parts of the cells' axial faces; a slanted roof covers no such face,
// so a cell under it reaches past the roof to the model's boundary and the flood seems to leak; so does a
// cell joining the walk to a wall's hollow core (the apartment plan: 13 of its 22 openings). Here the same
// seeds flood a voxel grid in which every
// voxel a structure polygon or pane touches is closed (a conservative voxelization: a surface at any slant
// closes every voxel it crosses, so no 6-connected path passes it), and an opening of the boundary is a
// leak only where this flood reaches the outside beyond it too.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/visibility/inside_flood.hpp"

namespace walk::compiler {

// Voxel side (metres): half the flood's least width, so a gap under kFloodVoxel is closed wherever it lies
// and one over 2 kFloodVoxel (kFloodMinWidth, where a person passes) is open.
inline constexpr double kFloodVoxel = kFloodMinWidth / 2.0;
// The grid's voxels at most (a byte each): a larger model gets larger voxels.
inline constexpr std::size_t kMaxFloodVoxels = std::size_t(1) << 26;

struct VoxelFlood {
  Box bounds;  // of the grid: the model's bounds and one layer of voxels round them, the outside
  double voxel = 0.0;
  std::array<int, 3> dims{};
  std::vector<char> closed, reached;  // per voxel, x fastest
  [[nodiscard]] std::size_t index(int x, int y, int z) const {
    return (std::size_t(z) * std::size_t(dims[1]) + std::size_t(y)) * std::size_t(dims[0]) + std::size_t(x);
  }
  // The voxel holding coordinate `x` on `axis`, clamped into the grid.
  [[nodiscard]] int voxel_of(double x, int axis) const;
  // Did the flood reach the outside layer of voxels beyond `face`, a rectangle flat on `axis` in the
  // plane of the model's bounds (their max side or min side)? The flood stops at that layer, so an
  // opening elsewhere does not reach round to this one.
  [[nodiscard]] bool reaches_beyond(const Box& face, int axis, bool max_side) const;
};

// Does the triangle meet the box (centre, half sides)? Separating axes (Akenine-Moller 2001): the box's
// three, the triangle's normal and the nine edge-by-axis crosses; touching counts as meeting.
[[nodiscard]] bool triangle_meets_box(const std::array<model::Vec3, 3>& triangle, const model::Vec3& centre,
                                      const model::Vec3& half);

// Floods from `seeds` (a seed in a closed voxel starts nothing) over a grid of `bounds` (the model's) in
// which the triangles of `polygons` [0, structure) that block sight or are glass close what they touch.
[[nodiscard]] VoxelFlood flood_voxels(std::span<const VisPolygon> polygons, std::size_t structure,
                                      const Box& bounds, std::span<const model::Vec3> seeds);

}  // namespace walk::compiler
