#pragma once
// Solids for the cells stage (model::Solid: convex volumes solid all through, such as Quake's world brushes)
// in the form it asks questions of: their planes, their box, and their section by an axial plane, which
// closes the part of a cell face that lies inside a wall.
#include <polyclipping/clipper.hpp>
#include <span>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct SolidVolume {
  std::vector<Plane> planes;  // one per face, normal pointing out (distance > 0 outside)
  std::vector<Winding> faces;
  Box box;
};

// Faces with no area (fewer than three corners, collinear) are left out; a solid with fewer than four
// faces left encloses nothing and is dropped.
[[nodiscard]] std::vector<SolidVolume> solid_volumes(std::span<const model::Solid> solids);

// Is `p` inside or within `tolerance` (metres) outside every face plane?
[[nodiscard]] bool solid_contains(const SolidVolume& solid, const model::Vec3& p, double tolerance);

// The solid's section by the plane p[axis] = coord, in that plane's Clipper coordinates (axial_cover.hpp),
// counter-clockwise; empty where the plane misses the solid or meets it along an edge or a corner only.
[[nodiscard]] ClipperLib::Path solid_section(const SolidVolume& solid, int axis, double coord);

}  // namespace walk::compiler
