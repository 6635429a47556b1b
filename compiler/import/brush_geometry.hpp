#pragma once
// Convex brushes from planes, in double precision: each face is the brush's plane clipped by all the others
// (the plane-intersection step of a BSP compiler). Corners of one brush closer than kBrushWeld are welded
// into one, so neighbouring faces share exact corners (no cracks) and faces that shrink below the weld
// distance (slivers from nearly coincident planes) disappear instead of leaving thin triangles.
#include <array>
#include <cstddef>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

// Distances in file units (Quake: 1 unit = 1 inch). Points closer than kClipEpsilon to a plane lie on it:
// map coordinates are integers or short decimals, so 1e-3 is far above round-off (~1e-12 at 4096) and far
// below any real feature.
inline constexpr double kClipEpsilon = 1e-3;
// Corners of one brush closer than this are one corner: 0.01 inch (0.25 mm), well below the 1-unit grid
// that level editors snap to, well above the error of intersecting nearly parallel planes.
inline constexpr double kBrushWeld = 1e-2;
// Half the side of the square each face starts from before clipping: larger than any map (Quake limits
// coordinates to +-4096); a face reaching beyond half of it means the brush is not closed.
inline constexpr double kBaseWinding = 1 << 20;

struct BrushPlane {
  model::Vec3 normal{0.0, 0.0, 1.0};  // unit, pointing out of the brush
  double dist = 0.0;                  // dot(normal, x) == dist on the plane
};

struct BrushFace {
  std::vector<model::Vec3> winding;  // counter-clockwise seen from outside
  std::size_t plane = 0;             // index into the input planes
};

struct ConvexBrush {
  std::vector<BrushPlane> planes;  // one per input plane; unused ones have no face
  std::vector<BrushFace> faces;
  model::Bounds bounds;
};

struct BrushStats {
  std::size_t degenerate_planes = 0;  // three collinear points: no plane
  std::size_t duplicate_planes = 0;   // same plane twice in one brush
  std::size_t open_brushes = 0;       // planes that do not close a volume: skipped
  std::size_t empty_brushes = 0;      // planes that enclose nothing: skipped
  std::size_t sliver_faces = 0;       // faces that collapsed when corners were welded
  std::size_t welded_corners = 0;     // corners merged into a nearby one
};

// The plane through three points, normal (p0 - p1) x (p2 - p1) as Quake's tools define it. False when the
// points are (nearly) collinear.
bool plane_from_points(const std::array<model::Vec3, 3>& p, BrushPlane& out);

// Keeps the part of `winding` behind `plane` (dot(n, x) <= dist + epsilon); `front` gets the rest when given.
std::vector<model::Vec3> clip_winding(const std::vector<model::Vec3>& winding, const BrushPlane& plane,
                                      std::vector<model::Vec3>* front = nullptr);

// Builds a brush's faces. False (and a count in `stats`) for a brush that is open or empty.
bool build_brush(const std::vector<std::array<model::Vec3, 3>>& plane_points, ConvexBrush& out,
                 BrushStats& stats);

}  // namespace walk::compiler
