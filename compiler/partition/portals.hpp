#pragma once
// Portals: the parts of each cell's boundary that no opaque polygon covers, as real polygons (Clipper
// booleans in the boundary plane), each joining the cell behind it to the cell in front. Glass covers
// nothing for sight, but closes a hole for the leak check: the building's outer boundary (its bounding box)
// left open by both opaque and glass polygons is a leak, reported with where it is.
#include <cstdint>
#include <limits>
#include <vector>

#include "compiler/partition/partition.hpp"
#include "compiler/partition/solid_volumes.hpp"

namespace walk::compiler {

inline constexpr std::uint32_t kOutside = std::numeric_limits<std::uint32_t>::max();
// Openings narrower than twice this (metres) are float cracks between abutting polygons, not portals.
inline constexpr double kCrackRadius = 5e-4;

struct Portal {
  std::uint32_t back = 0;   // cell on the -axis side
  std::uint32_t front = 0;  // cell on the +axis side
  int axis = 0;
  double coord = 0.0;
  std::vector<Winding> outline;  // outer loop then its holes, in the plane (3D)
  Winding hull;                  // convex hull of the outer loop: what the portal flow uses (conservative)
  double area = 0.0;             // square metres, holes subtracted
  bool glazed = false;           // wholly covered by glass
  // Which way sight lines pass: from `back` into `front`, and from `front` into `back`. With back faces
  // culled, an opaque polygon blocks only the sight lines that meet its front; where a face of the cell
  // boundary is covered by polygons facing one way only, the portal there is one-way.
  bool forward = true;
  bool backward = true;
  // Do sight lines pass from `cell` (one of its two) out through it?
  [[nodiscard]] bool open_from(std::uint32_t cell) const { return cell == back ? forward : backward; }
  // Its plane with the normal pointing out of `cell` (one of its two).
  [[nodiscard]] Plane out_of(std::uint32_t cell) const {
    return axial_plane(axis, coord, cell == back ? 1.0 : -1.0);
  }
};

struct Leak {
  model::Vec3 where{0.0};  // local coordinates: a point in the opening
  double area = 0.0;
  std::uint32_t cell = 0;  // the cell the opening belongs to
  int axis = 0;
  bool max_side = false;  // on the bounding box's +axis face
};

struct PortalGraph {
  std::vector<Portal> portals;
  std::vector<std::vector<std::uint32_t>> cell_portals;  // portal ids touching each cell
  std::vector<Leak> leaks;
};

// With `cull_back_faces` (the renderer's default), the parts of a face covered only by polygons facing one
// way become one-way portals as well. The sections of `solids` close every face they cut, leaks included.
[[nodiscard]] PortalGraph find_portals(const Partition& partition, const std::vector<VisPolygon>& polygons,
                                       bool cull_back_faces = false,
                                       std::span<const SolidVolume> solids = {});

}  // namespace walk::compiler
