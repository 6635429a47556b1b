#pragma once
// 2D booleans in an axial plane with Clipper: which part of a rectangle the polygons lying in that plane
// cover.
#include <polyclipping/clipper.hpp>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"

namespace walk::compiler {

// Clipper units per metre in axial-plane booleans (1 um; local coordinates stay within ~1e9 units).
inline constexpr double kAxialClipperScale = 1e6;

// In-plane axes of an axial plane normal to `axis`: (axis+1)%3 and (axis+2)%3, right-handed.
[[nodiscard]] inline int u_axis(int axis) {
  return (axis + 1) % 3;
}
[[nodiscard]] inline int v_axis(int axis) {
  return (axis + 2) % 3;
}

// The point (u, v) of an axial plane in Clipper units.
[[nodiscard]] ClipperLib::IntPoint axial_point(double u, double v);
[[nodiscard]] ClipperLib::Path rect_path(const Box& box, int axis);
// Union of the triangles of `ids` projected onto the plane normal to `axis`.
[[nodiscard]] ClipperLib::Paths union_of(const std::vector<std::uint32_t>& ids,
                                         const std::vector<VisPolygon>& polygons, int axis,
                                         const Box* clip_to);
[[nodiscard]] double area_of(const ClipperLib::Paths& paths);  // square metres, holes subtracted
// Removes features thinner than 2*radius (float cracks between abutting polygons) by an opening.
[[nodiscard]] ClipperLib::Paths open_region(const ClipperLib::Paths& paths, double radius);

}  // namespace walk::compiler
