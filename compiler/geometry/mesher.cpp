// Triangulation by slabs. Why not ear clipping: Debian has no packaged C++ earcut, a hand-written ear clipper
// needs its own care for holes (bridges), collinear and touching vertices, and we already depend on Clipper,
// whose booleans are robust on exactly those cases. Clipper cleans the outline and subtracts the holes;
// horizontal lines through every vertex then leave a row of trapezoids per slab (trapezoids.hpp), merged
// back into larger convex pieces where possible; a convex piece is trivially fanned. The same lines, plus
// vertical ones, dice the mesh to a grid for lighting resolution.
#include "compiler/geometry/mesher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <utility>

#include "compiler/geometry/clipper_convert.hpp"
#include "compiler/geometry/convex_fan.hpp"
#include "compiler/geometry/plane_frame.hpp"
#include "compiler/geometry/trapezoids.hpp"

namespace walk::compiler {
namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using Triangle2 = std::array<IntPoint, 3>;

// Grid lines (multiples of `cell`) strictly between lo and hi.
std::vector<cInt> grid_lines(cInt lo, cInt hi, cInt cell) {
  std::vector<cInt> out;
  if (cell <= 0) return out;
  const cInt first = (lo >= 0 ? lo / cell : -((-lo + cell - 1) / cell)) * cell;
  for (cInt g = first; g < hi; g += cell) {
    if (g > lo) out.push_back(g);
  }
  return out;
}

// `lines` with each one closer than kMinGridGap to one of `vertex_coordinates` (sorted) moved onto it.
std::vector<cInt> snapped(std::vector<cInt> lines, const std::vector<cInt>& vertex_coordinates) {
  const cInt gap = std::llround(kMinGridGap * kClipperScale);
  for (cInt& g : lines) {
    const auto it = std::lower_bound(vertex_coordinates.begin(), vertex_coordinates.end(), g - gap);
    if (it == vertex_coordinates.end() || *it >= g + gap) continue;
    cInt nearest = *it;  // the closest within the gap
    for (auto next = it + 1; next != vertex_coordinates.end() && *next < g + gap; ++next) {
      if (std::llabs(*next - g) < std::llabs(nearest - g)) nearest = *next;
    }
    g = nearest;
  }
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

// Where segment ab meets the vertical line x (a.X != b.X); computed from the segment's end points in a fixed
// order, so the pieces on both sides of the line get the very same point.
IntPoint at_x(IntPoint a, IntPoint b, cInt x) {
  if (b.X < a.X || (b.X == a.X && b.Y < a.Y)) std::swap(a, b);
  if (x == a.X) return a;
  if (x == b.X) return b;
  const long double t = static_cast<long double>(x - a.X) / static_cast<long double>(b.X - a.X);
  return {
      x, static_cast<cInt>(std::llround(static_cast<double>(a.Y + t * static_cast<long double>(b.Y - a.Y))))};
}

// The part of a convex piece with x >= limit (keep_right) or x <= limit (Sutherland-Hodgman, one line).
Path clip_x(const Path& piece, cInt limit, bool keep_right) {
  Path out;
  const auto inside = [&](const IntPoint& p) { return keep_right ? p.X >= limit : p.X <= limit; };
  auto add = [&](const IntPoint& q) {
    if (out.empty() || !(out.back() == q)) out.push_back(q);
  };
  for (std::size_t i = 0; i < piece.size(); ++i) {
    const IntPoint& a = piece[i];
    const IntPoint& b = piece[(i + 1) % piece.size()];
    if (inside(a)) add(a);
    if (inside(a) != inside(b) && a.X != limit && b.X != limit) add(at_x(a, b, limit));
  }
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

// An edge keeps a coordinate constant when its corners differ in it by at most this (metres): corners met by
// plane intersections in double (the Quake reader's CSG) differ by about 1e-15 m where they should agree.
// Placing a dicing point's coordinate from such corners moves it by at most this, far below float's rounding
// (5e-7 m at 8 m from the origin).
constexpr double kConstantCoordinateNoise = 1e-9;

// The region's boundary edges with their exact 3D end points. A dicing point on a boundary edge takes the
// coordinates that edge keeps constant from its corners (interpolated along it), instead of from its integer
// coordinates: those are rounded to 1 um in the plane's frame, which for a slanted wall is not the model's
// frame, so a point on the wall's vertical end edge came back up to a micrometre off it in x and y, and the
// crack between it and the perpendicular wall let sight lines through a corner. Constant to a rounding, not
// bit for bit: E1M1's 45-degree ceiling strips share an edge along x whose corners' z differ by 1e-15 m, so
// each strip's dicing points kept y but took z from the plane frame, 1e-7 m apart, and float rounding opened
// a crack between the strips. Only those coordinates: moving a point onto a slanted edge's line flipped
// slivers that the column cuts leave beside it (T-junction repair closes slanted seams between coplanar faces
// instead).
class BoundaryEdges {
 public:
  BoundaryEdges(const Paths& region, const PointMap& points) : points_(points) {
    for (const auto& path : region)
      for (std::size_t i = 0; i < path.size(); ++i) {
        const IntPoint& a = path[i];
        const IntPoint& b = path[(i + 1) % path.size()];
        if (points.exact(a) && points.exact(b) && !(a == b))
          edges_.push_back({a, b, points.to_3d(a), points.to_3d(b)});
      }
  }
  [[nodiscard]] model::Vec3 place(const IntPoint& p) const {
    if (points_.exact(p)) return points_.to_3d(p);
    for (const Edge& e : edges_) {
      const double dx = double(e.b.X - e.a.X), dy = double(e.b.Y - e.a.Y);
      const double px = double(p.X - e.a.X), py = double(p.Y - e.a.Y);
      const double length2 = dx * dx + dy * dy;
      const double t = (px * dx + py * dy) / length2;
      const double cross = px * dy - py * dx;  // distance from the edge's line times its length
      // Within one unit: the rounding of a cut through the edge (trapezoid and column cuts round to 0.5).
      if (t >= 0.0 && t <= 1.0 && cross * cross <= length2) {
        model::Vec3 q = points_.to_3d(p);
        for (int k = 0; k < 3; ++k)
          if (std::abs(e.A[k] - e.B[k]) <= kConstantCoordinateNoise) q[k] = e.A[k] + t * (e.B[k] - e.A[k]);
        return q;
      }
    }
    return points_.to_3d(p);
  }

 private:
  struct Edge {
    IntPoint a, b;
    model::Vec3 A, B;
  };
  const PointMap& points_;
  std::vector<Edge> edges_;
};

}  // namespace

model::Vec3 polygon_normal(const std::vector<model::Vec3>& vertices) {
  const model::Vec3 n = model::area_vector(vertices);
  const double length = glm::length(n);
  if (!(length > 0.0) || !std::isfinite(length)) return model::Vec3{0.0};
  return n / length;
}

PolygonMesh mesh_polygon(const model::Polygon& polygon, double cell_size) {
  PolygonMesh mesh;
  PlaneFrame frame;
  if (!plane_frame(polygon.vertices, frame)) {
    mesh.normal = model::Vec3{0.0};
    return mesh;
  }
  mesh.normal = frame.normal;
  PointMap points(frame);

  // The region: outer boundary minus holes, whatever their winding; touching or overlapping holes are fine.
  ClipperLib::Clipper clipper;
  Path outer = points.to_path(polygon.vertices);
  if (outer.size() < 3) return mesh;
  if (!ClipperLib::Orientation(outer)) ClipperLib::ReversePath(outer);
  clipper.AddPath(outer, ClipperLib::ptSubject, true);
  for (const auto& hole : polygon.holes) {
    Path path = points.to_path(hole);
    if (path.size() < 3) continue;
    if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
    clipper.AddPath(path, ClipperLib::ptClip, true);
  }
  Paths region;
  clipper.Execute(ClipperLib::ctDifference, region, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  if (region.empty()) return mesh;

  const cInt cell = cell_size > 0.0 ? std::max<cInt>(1, std::llround(cell_size * kClipperScale)) : 0;
  std::vector<cInt> xs, ys;
  for (const auto& path : region) {
    for (const auto& p : path) {
      xs.push_back(p.X);
      ys.push_back(p.Y);
    }
  }
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  const std::vector<cInt> column_lines = snapped(grid_lines(xs.front(), xs.back(), cell), xs);
  const Paths pieces = convex_pieces(region, snapped(grid_lines(ys.front(), ys.back(), cell), ys));

  std::vector<Triangle2> triangles;
  for (const auto& piece : pieces) {
    if (cell <= 0) {
      fan_convex(piece, triangles);
      continue;
    }
    cInt x0 = piece[0].X, x1 = x0;
    for (const auto& p : piece) {
      x0 = std::min(x0, p.X);
      x1 = std::max(x1, p.X);
    }
    Path rest = piece;  // what is right of the columns cut so far
    for (auto it = std::upper_bound(column_lines.begin(), column_lines.end(), x0);
         it != column_lines.end() && *it < x1; ++it) {
      const cInt g = *it;
      const Path column = clip_x(rest, g, false);
      if (column.size() >= 3) fan_convex(column, triangles);
      rest = clip_x(rest, g, true);
    }
    if (rest.size() >= 3) fan_convex(rest, triangles);
  }

  // Weld by exact integer position; map back to 3D (original vertices come back exactly, dicing points on
  // the boundary onto its edges, the rest onto the plane).
  const BoundaryEdges boundary(region, points);
  std::map<std::pair<cInt, cInt>, std::uint32_t> index_of;
  for (const auto& triangle : triangles) {
    for (const auto& p : triangle) {
      const auto [it, added] =
          index_of.emplace(std::make_pair(p.X, p.Y), static_cast<std::uint32_t>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(boundary.place(p));
      mesh.triangles.push_back(it->second);
    }
  }
  return mesh;
}

}  // namespace walk::compiler
