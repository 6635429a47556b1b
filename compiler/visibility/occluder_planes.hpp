#pragma once
// Occluders fused by plane: the opaque polygons of a model grouped by the plane they lie in, and united in
// that plane with Clipper, once per facing. A wall made of many polygons (cut round a door, diced, drawn
// as pieces by the exporter) then hides as one surface: the single-polygon test of occluders.hpp cannot
// see that three pieces of a wall together cover a window's view of the room behind.
//
// The test: every segment from a convex viewer region S to a convex target T crosses the plane's cover,
// when S lies strictly in front of the plane and T behind it. The crossings of all those segments are the
// plane's section of the convex hull of S and T, which is the convex hull of the crossings of the segments
// between their vertices (an edge of that hull crossing the plane joins a vertex of S to one of T). So the
// test is one 2D hull and one containment test (cover_index.hpp), exact up to kShaftSlack.
#include <cstdint>
#include <polyclipping/clipper.hpp>
#include <span>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/visibility/cover_index.hpp"

namespace walk::compiler {

// Metres. Points of a polygon within this of a plane lie in it, a target within this of the plane touches
// it, and what is left of a shaft's crossing after the cover is subtracted counts only where it is wider
// than twice this. Bundle coordinates are float, rounded to about 1e-6 m in a 10 m building: the slack is
// ten of those roundings, and 1/300 of a pixel's footprint at 1 m in a 512-pixel, 90-degree view, so a
// sliver of sight it lets pass covers a pixel centre about once in 300 pixels along a grazing edge.
inline constexpr double kShaftSlack = 1e-5;

struct OccluderPlane {
  Plane plane;                 // unit normal with its first clear component positive
  model::Vec3 origin, u, v;    // 2D frame in the plane: p -> ((p - origin).u, (p - origin).v)
  ClipperLib::Paths cover[3];  // united opaque polygons facing -normal, +normal, either; Clipper units
  CoverIndex index[3];         // each cover, for the containment test
  double lo[3][2], hi[3][2];   // bounds of each cover in (u, v), metres
  [[nodiscard]] bool has(int facing) const { return !cover[facing].empty(); }
};

// Where the sight lines between a source and a target cross an occluder plane.
struct Shaft {
  bool applies = false;        // the source lies in front of the plane and the target behind it
  bool blocked = false;        // every crossing lies in the cover
  double section_area = 0.0;   // of the crossings' convex hull, m^2
  std::vector<Winding> leaks;  // convex hulls of the uncovered parts (asked for)
  double leak_area = 0.0;      // theirs, m^2
  // Kept for OccluderPlanes::find_leaks: the section in Clipper units, its bounds, the cover's facing.
  ClipperLib::Path section;
  ClipperLib::IntPoint section_lo, section_hi;
  int facing = 0;
};

class OccluderPlanes {
 public:
  // With `cull_back_faces` a polygon blocks only sight lines that meet its front (the renderer does not
  // draw its back, and shows what lies behind).
  OccluderPlanes(const std::vector<VisPolygon>& polygons, bool cull_back_faces);

  // The plane a polygon occludes in; -1 for glass, non-planar or degenerate polygons.
  [[nodiscard]] int plane_of(std::uint32_t polygon) const {
    return polygon < plane_of_.size() ? plane_of_[polygon] : -1;
  }
  [[nodiscard]] const OccluderPlane& operator[](std::size_t i) const { return planes_[i]; }
  [[nodiscard]] std::size_t size() const { return planes_.size(); }

  // Does every segment from a point of `source` to a point of `target` cross the cover of plane `i` that
  // faces the source (either facing without back-face culling)? Both are convex, given by their vertices:
  // a box's corners, a portal's or polygon's winding. False when the source does not lie wholly on one side
  // of the plane, by more than kShaftSlack, and the target wholly on the other (touching the plane
  // allowed; a target lying in the plane never counts as hidden by it).
  [[nodiscard]] bool blocks(std::size_t i, std::span<const model::Vec3> source, const Winding& target) const;
  // The same test, with the parts of the plane's section the cover leaves open when `want_leaks`: a sight
  // line that is not blocked there passes through one of them.
  [[nodiscard]] Shaft shaft(std::size_t i, std::span<const model::Vec3> source, const Winding& target,
                            bool want_leaks) const;
  // The leaks of a shaft of plane `i` asked without them, as shaft(..., true) finds them: a proof tests the
  // plane first and wants its open parts only when no plane blocks.
  void find_leaks(std::size_t i, Shaft& shaft) const;

 private:
  bool cull_back_faces_;
  std::vector<OccluderPlane> planes_;
  std::vector<int> plane_of_;
};

}  // namespace walk::compiler
