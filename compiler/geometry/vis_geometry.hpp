#pragma once
// Geometry the visibility stages share: axis-aligned boxes, planes, convex windings and their clipping,
// the drawn polygons of a bundle in double precision.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Points closer than this to a plane count as on it (10 um: above float rounding of bundle coordinates in a
// 1 km building, 6e-5 m relative... well below any wall thickness). Clipping keeps "on" points, so it errs
// towards seeing more: conservative.
inline constexpr double kPlaneEpsilon = 1e-5;
// Polygons whose vertices lie within this of a plane are in that plane (float bundle coordinates are
// rounded to ~1e-7 relative: 0.1 mm at 1 km).
inline constexpr double kInPlaneTolerance = 1e-4;
// A polygon normal within this (cosine) of an axis is axial: a candidate splitting plane.
inline constexpr double kAxialCosine = 0.99999;

struct Box {
  model::Vec3 min{0.0};
  model::Vec3 max{0.0};
  [[nodiscard]] bool contains(const model::Vec3& p, double tol = 0.0) const;
  [[nodiscard]] bool overlaps(const Box& o, double tol) const;
  [[nodiscard]] model::Vec3 size() const { return max - min; }
};

struct Plane {
  model::Vec3 n{0.0, 0.0, 1.0};
  double d = 0.0;  // n.p + d = 0
  [[nodiscard]] double distance(const model::Vec3& p) const { return n.x * p.x + n.y * p.y + n.z * p.z + d; }
  [[nodiscard]] Plane flipped() const { return {-n, -d}; }
};

// The plane p[axis] = coord with its normal along +axis (sign > 0) or -axis (otherwise). Use this rather than
// setting n[axis] on a default Plane, whose normal is +z.
[[nodiscard]] Plane axial_plane(int axis, double coord, double sign);

using Winding = std::vector<model::Vec3>;  // convex, planar

// Keeps the part of `w` on the front side of `p` (distance >= -kPlaneEpsilon); points within epsilon count
// as on the plane and stay. Empty when all of `w` is behind.
[[nodiscard]] Winding clip_front(const Winding& w, const Plane& p);
// clip_front by each plane in turn; empty as soon as nothing is left.
[[nodiscard]] Winding clip_front_all(Winding w, const std::vector<Plane>& planes);

// Convex hull of planar points, as a winding in their plane (counter-clockwise about `normal`). Fewer than
// three distinct points, or collinear ones, give the distinct extreme points (a degenerate winding).
[[nodiscard]] Winding convex_hull(const std::vector<model::Vec3>& points, const model::Vec3& normal);

// Quake vis's separating planes between `source` and `pass`: a plane through an edge of source and a point
// of pass with source behind and pass in front; `flip` reverses them. Degenerate planes are skipped.
void separating_planes(const Winding& source, const Winding& pass, bool flip, std::vector<Plane>& out);

// The part of `dest` that a sight line from a point of `source` (a convex region's vertices: a winding or
// a box's corners) through a point of `window` (a convex winding) reaches beyond the window; the source
// lies in front of the window's plane, dest behind it. A plane with all of the source behind it and all of
// the window in front has every such line's continuation in front too (Quake vis's separating planes, as
// the portal flow clips what a pass portal lets through), so dest is clipped by each. Each is first moved
// back to the source's farthest point, and kept only while the window lies in front of it to within a
// slack that a line's run past the window cannot grow beyond kPlaneEpsilon (clip_front's own): a line's
// distance from the plane grows by at most reach / gap times the window's, where gap is the source's least
// distance from the window's plane. Dest whole when the source touches that plane or the window is
// degenerate; empty when no such line reaches it.
[[nodiscard]] Winding reached_through(std::span<const model::Vec3> source, const Winding& window,
                                      Winding dest);

// A drawn polygon of the bundle (opaque, glass, luminaire panel) in double precision.
struct VisPolygon {
  std::vector<std::array<model::Vec3, 3>> triangles;
  // Triangles the display draws for it: what leaving it out of a view saves. `triangles` may be fewer
  // over the same surface (the coarse form, which the cells stage works on).
  std::size_t drawn_triangles = 0;
  Winding hull;  // convex hull of its vertices in its plane: conservative stand-in for visibility tests
  model::Vec3 normal{0.0};
  Box box;
  bool opaque = false;  // blocks sight lines (glass does not)
  bool glass = false;
  bool detail = false;  // a detail cluster (vis_items.hpp): seen by its box, hides nothing, splits nothing
  int axis = -1;        // 0..2 when the polygon lies in an axial plane
  double coord = 0.0;   // its plane's coordinate on that axis
};

// Width of a convex planar winding (m): the least, over its edges, of the farthest vertex from the edge's
// line. 0 for fewer than three points or collinear ones.
[[nodiscard]] double winding_width(const Winding& w);

// Area of a planar winding (m^2), measured about the unit `normal` of its plane.
[[nodiscard]] double winding_area(const Winding& w, const model::Vec3& normal);
// Does `p` fill its hull? Their areas agree to 1e-6 (a notch or a hole makes the hull larger by its area).
// Then every piece of the hull meets the polygon, and the hull may stand for it as an occluder.
[[nodiscard]] bool fills_hull(const VisPolygon& p);

// Does every triangle of `p` face away from every point of `box` (the box on or behind each triangle's
// plane)? Then a renderer that culls back faces never draws `p` from anywhere in the box. Degenerate
// triangles (no area, nothing to draw) do not count against it.
[[nodiscard]] bool faces_away_from(const VisPolygon& p, const Box& box);

[[nodiscard]] std::vector<VisPolygon> vis_polygons(std::span<const model::VertexRecord> vertices,
                                                   std::span<const std::uint32_t> indices,
                                                   std::span<const model::PolygonRecord> polygons);

}  // namespace walk::compiler
