#include "compiler/partition/portals.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "compiler/partition/axial_cover.hpp"
#include "compiler/partition/solid_volumes.hpp"

namespace walk::compiler {
namespace {

// Cell faces within this (metres) of each other are the same plane: they come from one split coordinate,
// so they agree exactly; the tolerance only absorbs nothing-but-rounding.
constexpr double kFaceTolerance = 1e-9;
// Glass this close to a face (metres: a thick wall) closes the face where it covers it: a pane set in a
// window's reveal closes the hole in the wall's faces. Glass hides nothing, so this only decides where the
// inside flood and the leak check may pass, never what is seen.
constexpr double kGlassReach = 0.5;
// Openings smaller than this (m^2) after crack removal are ignored (1 cm^2: a pixel at most).
constexpr double kMinOpeningArea = 1e-4;

model::Vec3 to_3d(const ClipperLib::IntPoint& p, int axis, double coord) {
  model::Vec3 q{0.0};
  q[axis] = coord;
  q[u_axis(axis)] = double(p.X) / kAxialClipperScale;
  q[v_axis(axis)] = double(p.Y) / kAxialClipperScale;
  return q;
}

ClipperLib::Paths subtract(const ClipperLib::Paths& a, const ClipperLib::Paths& b) {
  if (b.empty()) return a;
  ClipperLib::Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  ClipperLib::Paths out;
  c.Execute(ClipperLib::ctDifference, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// Face rectangle shared by two cells, as a Box flat on the axis.
Box shared_face(const Box& a, const Box& b, int axis, double coord) {
  Box r;
  for (int k = 0; k < 3; ++k) {
    r.min[k] = std::max(a.min[k], b.min[k]);
    r.max[k] = std::min(a.max[k], b.max[k]);
  }
  r.min[axis] = r.max[axis] = coord;
  return r;
}

// What can close a face, each united once (the unions over diced triangles are the expensive part): the
// opaque polygons of its plane facing -axis, those facing +axis, the plane's glass, and the sections of the
// solids it cuts (closed every way: nothing sees or stands inside a solid).
struct FaceClosers {
  ClipperLib::Paths minus, plus, glass, solid;
};

FaceClosers face_closers(const Box& face, int axis, double coord, const Partition& part,
                         const std::vector<VisPolygon>& polygons, std::span<const SolidVolume> solids) {
  FaceClosers k;
  {
    ClipperLib::Clipper c;
    bool any = false;
    for (const auto& solid : solids) {
      // A solid ending within kPlaneEpsilon of the face closes it as one ending on it does: the face is the
      // bundle's float, the solid the model's double (DM1: an arch's brush 1 um short of a cell face left
      // its band open, joining the room below the arch to the void above it), and the open regions take
      // the voxels beside the face as solid within the same tolerance.
      if (!solid.box.overlaps(face, kPlaneEpsilon)) continue;
      const double at = std::clamp(coord, solid.box.min[axis], solid.box.max[axis]);
      ClipperLib::Path section = solid_section(solid, axis, at);
      if (section.empty()) continue;
      c.AddPath(section, ClipperLib::ptSubject, true);
      any = true;
    }
    if (any) {
      c.AddPath(rect_path(face, axis), ClipperLib::ptClip, true);
      c.Execute(ClipperLib::ctIntersection, k.solid, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    }
  }
  if (const AxialPlane* plane = find_plane(part.planes, axis, coord)) {
    std::vector<std::uint32_t> minus_ids, plus_ids;
    for (const auto id : plane->opaque)
      (polygons[id].normal[axis] < 0.0 ? minus_ids : plus_ids).push_back(id);
    k.minus = union_of(minus_ids, polygons, axis, &face);
    k.plus = union_of(plus_ids, polygons, axis, &face);
  }
  std::vector<std::uint32_t> glass;
  for (const auto& p : part.planes)
    if (p.axis == axis && std::abs(p.coord - coord) <= kGlassReach)
      glass.insert(glass.end(), p.glass.begin(), p.glass.end());
  k.glass = union_of(glass, polygons, axis, &face);
  return k;
}

// The open part of a face: its rectangle minus `closers`, cracks removed.
ClipperLib::Paths open_without(const Box& face, int axis,
                               std::initializer_list<const ClipperLib::Paths*> closers) {
  ClipperLib::Paths region{rect_path(face, axis)};
  for (const auto* c : closers) region = subtract(region, *c);
  return open_region(region, kCrackRadius);
}

}  // namespace

PortalGraph find_portals(const Partition& part, const std::vector<VisPolygon>& polygons, bool cull_back_faces,
                         std::span<const SolidVolume> solids) {
  PortalGraph g;
  g.cell_portals.resize(part.cells.size());
  const auto& cells = part.cells;
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    for (int axis = 0; axis < 3; ++axis) {
      const int u = u_axis(axis), v = v_axis(axis);
      // Neighbours across the +axis face.
      const double x = cells[c].max[axis];
      for (std::uint32_t d = 0; d < cells.size(); ++d) {
        if (d == c || std::abs(cells[d].min[axis] - x) > kFaceTolerance) continue;
        const Box face = shared_face(cells[c], cells[d], axis, x);
        if (face.max[u] - face.min[u] <= 0.0 || face.max[v] - face.min[v] <= 0.0) continue;
        const FaceClosers k = face_closers(face, axis, x, part, polygons, solids);
        const ClipperLib::Paths glass_open =
            open_without(face, axis, {&k.minus, &k.plus, &k.glass, &k.solid});
        // Portals over `open`, passable forward (back cell to front cell) and/or backward.
        auto emit = [&](const ClipperLib::Paths& open, bool forward, bool backward) {
          ClipperLib::PolyTree tree;
          ClipperLib::Clipper un;
          // Openings touching at a corner are separate portals (E1M1: a room's opening below a cornice and
          // the void's above it): as one, its outline joined both parts behind it into one region.
          un.StrictlySimple(true);
          un.AddPaths(open, ClipperLib::ptSubject, true);
          un.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
          for (const ClipperLib::PolyNode* outer : tree.Childs) {
            Portal p;
            p.back = c;
            p.front = d;
            p.axis = axis;
            p.coord = x;
            p.forward = forward;
            p.backward = backward;
            ClipperLib::Paths piece{outer->Contour};
            for (const auto* hole : outer->Childs) piece.push_back(hole->Contour);
            p.area = area_of(piece);
            if (p.area < kMinOpeningArea) continue;
            for (const auto& path : piece) {
              Winding w;
              for (const auto& q : path) w.push_back(to_3d(q, axis, x));
              p.outline.push_back(std::move(w));
            }
            model::Vec3 n{0.0};
            n[axis] = 1.0;
            p.hull = convex_hull(p.outline.front(), n);
            // Glazed when glass closes all of it.
            ClipperLib::Clipper g2;
            g2.AddPaths(glass_open, ClipperLib::ptSubject, true);
            g2.AddPaths(piece, ClipperLib::ptClip, true);
            ClipperLib::Paths left;
            g2.Execute(ClipperLib::ctIntersection, left, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
            p.glazed = area_of(left) < kMinOpeningArea;
            const auto id = static_cast<std::uint32_t>(g.portals.size());
            g.cell_portals[c].push_back(id);
            g.cell_portals[d].push_back(id);
            g.portals.push_back(std::move(p));
          }
        };
        const ClipperLib::Paths both = open_without(face, axis, {&k.minus, &k.plus, &k.solid});
        emit(both, true, true);
        if (cull_back_faces) {
          // A sight line going +axis meets the fronts of polygons facing -axis and passes the rest; where
          // only one facing covers the face, the portal is one-way.
          if (!k.plus.empty())
            emit(open_region(subtract(open_without(face, axis, {&k.minus, &k.solid}), both), kCrackRadius),
                 true, false);
          if (!k.minus.empty())
            emit(open_region(subtract(open_without(face, axis, {&k.plus, &k.solid}), both), kCrackRadius),
                 false, true);
        }
      }
      // The outer boundary: open parts there (neither opaque nor glass) are leaks.
      for (const bool max_side : {false, true}) {
        const double at = max_side ? cells[c].max[axis] : cells[c].min[axis];
        const double edge = max_side ? part.bounds.max[axis] : part.bounds.min[axis];
        if (std::abs(at - edge) > kFaceTolerance) continue;
        Box face = cells[c];
        face.min[axis] = face.max[axis] = at;
        const FaceClosers k = face_closers(face, axis, at, part, polygons, solids);
        for (const auto& path : open_without(face, axis, {&k.minus, &k.plus, &k.glass, &k.solid})) {
          const double area = std::abs(ClipperLib::Area(path)) / (kAxialClipperScale * kAxialClipperScale);
          if (area < kMinOpeningArea || !ClipperLib::Orientation(path)) continue;
          model::Vec3 centre{0.0};
          for (const auto& q : path) centre += to_3d(q, axis, at);
          g.leaks.push_back({centre / double(path.size()), area, c, axis, max_side});
        }
      }
    }
  }
  return g;
}

}  // namespace walk::compiler
