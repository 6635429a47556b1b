#pragma once
// Cells split into the open parts that solids leave in them (model::Solid, such as Quake's world brushes).
// An axial cell often straddles a wall: a room on one side, the next room or the void round a level on the
// other. As one convex cell it lets sight pass from one side to the other; as regions (the connected open
// parts of the cell, found on a voxel grid) a sight line entering through one portal leaves only through
// the portals of the part it entered. Flood, samples, flow and proofs then run over regions, and a cell's
// PVS is the union of its inside regions' (what a viewer anywhere in its open space may see).
//
// Conservative but for one bound: a voxel is solid when one solid holds it, so open points lie in open
// voxels, or, across a seam between solids, when solids hold a lattice of points through it (kSeamLattice in
// open_regions.cpp), which takes a gap between solids narrower than the lattice's step as closed. Voxels
// sharing a face join (6-neighbours: a segment through open space passes from voxel to voxel through faces,
// but along a measure-zero set of edges and corners) unless solids hold the face (one solid its four
// corners, or solids a lattice on it across a seam): no open point lies on it to pass through. A portal
// joins every region under its open area on each side, row by row of voxels (regions it meets twice on one
// side merge), and an item belongs to every region its box touches.
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/partition/portals.hpp"
#include "compiler/partition/solid_volumes.hpp"

namespace walk::compiler {

// Each cell's grid has a line at every axial face of the solids it meets, so a voxel lies wholly inside an
// axial solid or wholly outside it, and where two solids meet no open seam is left between them; more
// lines keep voxels at most kOpenVoxel (metres) on a side, so a slanted solid holds the voxels well inside
// it. A cell whose grid would pass kMaxVoxelsPerCell keeps every kth fill line only. The cap (32 M voxels,
// about 250 MB while one cell is labelled) keeps 0.2 m voxels in E1M1's largest cells (31 x 31 x 15 m): at
// 4 M they fell to 0.4 m, and voxels across thin slanted walls joined the rooms either side.
inline constexpr double kOpenVoxel = 0.2;
inline constexpr std::size_t kMaxVoxelsPerCell = std::size_t(1) << 25;
// Grid lines closer than this (metres) are one: the cell's faces come from the bundle's float coordinates and
// the solids' from the model's doubles, so a face meant to coincide with a cell's lies a few micrometres
// off it, and the sliver of voxels between them would be open space no viewer fits in (kPlaneEpsilon).
inline constexpr double kGridLineMerge = kPlaneEpsilon;

struct OpenRegions {
  // One "cell" per region: its box is the box of its open voxels, its polygons the items touching them.
  // `planes` and `bounds` are the cells'; `nodes` is empty (locate regions with locate()).
  Partition partition;
  PortalGraph graph;  // portals between regions (copies of the cells' portals), leaks by region
  std::vector<std::uint32_t> cell_of;                  // per region
  std::vector<std::vector<std::uint32_t>> regions_of;  // per cell
  std::uint64_t voxels = 0, solid_voxels = 0;
  std::size_t portals_dropped = 0;  // portals with no open voxel on a side (inside a wall)

  // The region holding `p` (local coordinates) in cell `cell`, or the nearest open one within two voxels;
  // kOutside when `p` is inside a solid.
  [[nodiscard]] std::uint32_t locate(std::uint32_t cell, const model::Vec3& p) const;
  // Is `p` in an open voxel of `region`?
  [[nodiscard]] bool holds(std::uint32_t region, const model::Vec3& p) const;

  struct Grid {
    std::vector<double> lines[3];      // per axis, increasing, from the cell's min to its max
    int n[3] = {1, 1, 1};              // voxels per axis: lines - 1
    std::vector<std::int32_t> region;  // per voxel, x fastest: its region, -1 solid
    [[nodiscard]] std::size_t index(int i, int j, int k) const {
      return (std::size_t(k) * std::size_t(n[1]) + std::size_t(j)) * std::size_t(n[0]) + std::size_t(i);
    }
    // The voxel along `a` holding coordinate x (clamped to the grid).
    [[nodiscard]] int at(int a, double x) const;
  };
  std::vector<Grid> grids;  // per cell
};

// Opaque structure items (of `polygons`) whose front only the void sees, as qbsp's outside fill finds the
// faces to drop: the void is the regions an outside flood reaches (from the openings of the model's
// bounding box, through every portal) and the inside flood does not (`inside`, per region). An item is
// void-facing when a point kVoidProbe in front of one of its triangles lies in the void or beyond the
// model's box and none lies on the walk; a probe in a solid voxel says nothing. Sorted.
inline constexpr double kVoidProbe = 0.02;  // metres: inside the first voxel before a face (kOpenVoxel)
[[nodiscard]] std::vector<std::uint32_t> void_facing_items(const OpenRegions& regions, const Partition& cells,
                                                           const std::vector<VisPolygon>& polygons,
                                                           const std::vector<char>& inside);

[[nodiscard]] OpenRegions open_regions(const Partition& partition, const PortalGraph& graph,
                                       const std::vector<VisPolygon>& polygons,
                                       std::span<const SolidVolume> solids, unsigned threads);

}  // namespace walk::compiler
