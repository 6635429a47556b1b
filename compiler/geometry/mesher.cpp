// Triangulation by slabs. Why not ear clipping: Debian has no packaged C++ earcut, a hand-written ear clipper
// needs its own care for holes (bridges), collinear and touching vertices, and we already depend on Clipper,
// whose booleans are robust on exactly those cases. Cutting the polygon into horizontal slabs at every
// vertex height leaves pieces that are convex (each is bounded by two edges that cross its slab and by the
// two slab lines), and a convex piece is trivially fanned. The same cut also dices the mesh to a grid for
// lighting resolution. Cost: more triangles than a minimal triangulation when cell_size <= 0.
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

namespace walk::compiler {
namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using Triangle2 = std::array<IntPoint, 3>;

// Slab cuts closer than this (metres) are merged: vertex heights that differ by less than a millimetre
// (print round-off, a window ending 1 mm short of its wall) would otherwise slice the whole polygon into
// sub-millimetre slivers. A millimetre is below anything visible at walkthrough distances and below a
// lighting cell by two orders of magnitude. Pieces that merging leaves non-convex are cut exactly instead.
constexpr double kMinSlabHeight = 1e-3;

constexpr cInt to_units(double metres) {
  return static_cast<cInt>(metres * kClipperScale);
}

Paths clip(const Paths& subject, cInt x0, cInt y0, cInt x1, cInt y1) {
  const Path box{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  ClipperLib::Clipper clipper;
  clipper.PreserveCollinear(true);  // keep vertices where neighbouring pieces meet: no T-junctions
  clipper.AddPaths(subject, ClipperLib::ptSubject, true);
  clipper.AddPath(box, ClipperLib::ptClip, true);
  Paths out;
  clipper.Execute(ClipperLib::ctIntersection, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// Sorted cut heights from `values`, merging those closer than `min_gap`, always keeping the first and last.
std::vector<cInt> merged_cuts(std::vector<cInt> values, cInt min_gap) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::vector<cInt> cuts;
  for (cInt y : values) {
    if (cuts.empty() || y - cuts.back() >= min_gap) cuts.push_back(y);
  }
  if (!values.empty() && cuts.back() != values.back()) {
    if (cuts.size() > 1 && values.back() - cuts.back() < min_gap)
      cuts.back() = values.back();
    else
      cuts.push_back(values.back());
  }
  return cuts;
}

// Grid lines (multiples of `cell`) strictly between lo and hi.
std::vector<cInt> grid_lines(cInt lo, cInt hi, cInt cell) {
  std::vector<cInt> out;
  if (cell <= 0) return out;
  cInt k = lo / cell - 1;
  for (cInt g = k * cell; g < hi; g += cell) {
    if (g > lo) out.push_back(g);
  }
  return out;
}

struct Slabber {
  Paths region;
  std::vector<cInt> vertex_ys;  // every distinct vertex height, unmerged
  cInt cell = 0;                // grid cell in Clipper units, 0 for none
  std::vector<Triangle2> triangles;

  // Splits the pieces of one slab into grid columns and fans them. Returns false when a piece is not convex
  // (or a hole lies inside the slab), leaving `triangles` unchanged.
  bool mesh_slab(cInt y0, cInt y1, bool exact) {
    const cInt x0 = bounds_lo_x - 1, x1 = bounds_hi_x + 1;
    Paths pieces = clip(region, x0, y0, x1, y1);
    for (const auto& piece : pieces) {
      if (!ClipperLib::Orientation(piece) || !is_convex(piece)) {
        if (!exact) return false;
      }
    }
    std::vector<Triangle2> out;
    for (const auto& piece : pieces) {
      if (!ClipperLib::Orientation(piece)) continue;  // only possible when exact: a sub-unit hole, dropped
      if (cell <= 0) {
        fan_convex(piece, out);
        continue;
      }
      cInt lo = piece[0].X, hi = piece[0].X;
      for (const auto& p : piece) {
        lo = std::min(lo, p.X);
        hi = std::max(hi, p.X);
      }
      std::vector<cInt> xs = grid_lines(lo, hi, cell);
      xs.insert(xs.begin(), lo);
      xs.push_back(hi);
      const Paths one{piece};
      for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
        for (const auto& column : clip(one, xs[i], y0, xs[i + 1], y1)) {
          if (ClipperLib::Orientation(column)) fan_convex(column, out);
        }
      }
    }
    triangles.insert(triangles.end(), out.begin(), out.end());
    return true;
  }

  void mesh_between(cInt y0, cInt y1) {
    if (mesh_slab(y0, y1, false)) return;
    // Merging put a reflex vertex or a small hole inside this slab: cut at every vertex height in it.
    std::vector<cInt> inner{y0, y1};
    for (cInt y : vertex_ys) {
      if (y > y0 && y < y1) inner.push_back(y);
    }
    std::sort(inner.begin(), inner.end());
    for (std::size_t i = 0; i + 1 < inner.size(); ++i) mesh_slab(inner[i], inner[i + 1], true);
  }

  cInt bounds_lo_x = 0, bounds_hi_x = 0;
};

}  // namespace

model::Vec3 polygon_normal(const std::vector<model::Vec3>& vertices) {
  if (vertices.size() < 3) return model::Vec3{0.0};
  // Newell's method, relative to the first vertex for precision far from the origin.
  const model::Vec3 o = vertices.front();
  model::Vec3 n{0.0};
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const model::Vec3 a = vertices[i] - o;
    const model::Vec3 b = vertices[(i + 1) % vertices.size()] - o;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
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
  Slabber slabber;
  clipper.Execute(ClipperLib::ctDifference, slabber.region, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  if (slabber.region.empty()) return mesh;

  cInt lo_y = slabber.region[0][0].Y, hi_y = lo_y;
  slabber.bounds_lo_x = slabber.bounds_hi_x = slabber.region[0][0].X;
  for (const auto& path : slabber.region) {
    for (const auto& p : path) {
      slabber.vertex_ys.push_back(p.Y);
      lo_y = std::min(lo_y, p.Y);
      hi_y = std::max(hi_y, p.Y);
      slabber.bounds_lo_x = std::min(slabber.bounds_lo_x, p.X);
      slabber.bounds_hi_x = std::max(slabber.bounds_hi_x, p.X);
    }
  }
  std::sort(slabber.vertex_ys.begin(), slabber.vertex_ys.end());
  slabber.vertex_ys.erase(std::unique(slabber.vertex_ys.begin(), slabber.vertex_ys.end()),
                          slabber.vertex_ys.end());
  slabber.cell =
      cell_size > 0.0 ? std::max<cInt>(1, static_cast<cInt>(std::llround(cell_size * kClipperScale))) : 0;

  std::vector<cInt> cut_values = slabber.vertex_ys;
  for (cInt g : grid_lines(lo_y, hi_y, slabber.cell)) cut_values.push_back(g);
  const std::vector<cInt> cuts = merged_cuts(std::move(cut_values), to_units(kMinSlabHeight));
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) slabber.mesh_between(cuts[i], cuts[i + 1]);

  // Weld by exact integer position; map back to 3D on the plane (original vertices come back exactly).
  std::map<std::pair<cInt, cInt>, std::uint32_t> index_of;
  for (const auto& triangle : slabber.triangles) {
    for (const auto& p : triangle) {
      const auto [it, added] =
          index_of.emplace(std::make_pair(p.X, p.Y), static_cast<std::uint32_t>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(points.to_3d(p));
      mesh.triangles.push_back(it->second);
    }
  }
  return mesh;
}

}  // namespace walk::compiler
