#pragma once
// Structure and detail, and the clusters a PVS lists. Only the building's shell (structure) shapes cells and
// portals and hides anything; detail (furniture, fixtures, small or curved pieces) is seen or not as a
// whole cluster, by its bounding box, and never hides anything (Quake's detail brushes, Teller's
// cell-to-object visibility). So the cells stage costs in clusters, not in triangles.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/partition/visibility_config.hpp"

namespace walk::compiler {

// Triangles a detail cluster holds at most: a few hundred, so that a cluster is one piece of one object.
inline constexpr std::size_t kClusterTriangles = 256;
// A detail cluster's box is split until no side is longer than this (metres): a long detail group (a
// handrail along a corridor) is seen piece by piece.
inline constexpr double kClusterExtent = 2.0;

// A group smaller than VisibilityConfig::detail_extent is still structure when its median face is at least
// this large (m^2): a small room's whole walls, not an object's facets.
inline constexpr double kShellFaceArea = 1.0;

struct VisItems {
  // What the cells stage works on: the structure polygons (one item each, in polygon order), then the detail
  // clusters (VisPolygon::detail: triangles and box, no hull; neither opaque nor a splitting plane).
  std::vector<VisPolygon> items;
  std::vector<std::vector<std::uint32_t>> polygons;  // per item, the bundle polygons it stands for (sorted)
  std::size_t structure = 0;                         // items [0, structure) are structure polygons
  std::size_t detail_polygons = 0;
};

// Is the polygon structure? Only polygons that block sight or are glass can be. A scene's `structure` /
// `detail` patterns on its group name decide first; then a door's or window's frame (config.frame_groups) is
// structure. Otherwise a polygon smaller than config.detail_area is
// detail, and so is one of a group that is small (box under config.detail_extent) and made of small faces
// (median under kShellFaceArea): an object. Glass is structure unless the `detail` pattern names it: it
// closes the envelope.
[[nodiscard]] std::vector<char> structure_polygons(const std::vector<VisPolygon>& polygons,
                                                   std::span<const model::PolygonRecord> records,
                                                   std::span<const std::string> group_names,
                                                   const VisibilityConfig& config);

// Items from the bundle's polygons (vis_polygons) and the structure flags: detail polygons of one group and
// kind (glass or not) are split by their boxes' centres, at the median of the longest side, until a
// cluster is small in triangles and in size.
[[nodiscard]] VisItems make_vis_items(std::vector<VisPolygon> polygons,
                                      std::span<const model::PolygonRecord> records,
                                      const std::vector<char>& structure);

// The eight corners of `box` (a point set, not a winding).
[[nodiscard]] std::vector<model::Vec3> box_corners(const Box& box);

// The faces of `box` (x min, x max, y, z), each a winding; a flat box has one face in its flat plane.
[[nodiscard]] std::vector<Winding> box_faces(const Box& box);

// The triangles of `box`'s surface, each facing out of it (counter-clockwise seen from outside); of a flat
// box's two faces in its flat plane only the one facing +axis (its sides have no area).
[[nodiscard]] std::vector<std::array<model::Vec3, 3>> box_shell(const Box& box);

// Does any part of `box` lie on the front side of every plane (the sight lines they bound)? Tested face by
// face: a convex region that meets a bounded box and is not inside it crosses one of its faces.
[[nodiscard]] bool box_meets_region(const Box& box, const std::vector<Plane>& planes);

}  // namespace walk::compiler
