#include "compiler/geometry/seal_gaps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <tuple>

#include "compiler/geometry/clipper_convert.hpp"
#include "compiler/geometry/plane_frame.hpp"

namespace walk::compiler {
namespace {

// Grouping key resolution for unit normals (faces of one plane agree to about 1e-6).
constexpr double kNormalKey = 1e5;
// What the closing leaves besides real slits: slivers a rounding (1 um) wide along every boundary. A slit
// is kept when its mean width, twice its area over its perimeter, is at least this (metres)...
constexpr double kMinSlitWidth = 1e-5;
// ...and its area at least this (square metres: a 0.1 mm square).
constexpr double kMinSlitArea = 1e-8;
// A slit's fill reaches this far (metres) under the faces beside it, rather than meeting them edge to edge:
// the slit's outline comes out of Clipper's offsets rounded to 1 um off the faces' edges, which left
// micrometre cracks, and T-junction repair inserting its rounded corners into their edges flipped slivers.
// Overlapping coplanar faces are harmless (same plane, same side; the ray caster's tie rule picks one).
constexpr double kSealOverlap = 5e-5;
// Before that, the fill sheds what is thinner than twice this: the rounding slivers the closing leaves
// along the faces' edges, attached to the slit.
constexpr double kSliver = 5e-6;

double perimeter(const ClipperLib::Path& path) {
  double p = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto& a = path[i];
    const auto& b = path[(i + 1) % path.size()];
    p += std::hypot(double(b.X - a.X), double(b.Y - a.Y));
  }
  return p / kClipperScale;
}

}  // namespace

std::string SealStats::summary() const {
  return fmt::format("planes {} slits sealed {} ({:.4f} m2)", planes, faces_added, area);
}

SealStats seal_gaps(model::Model& model, double width) {
  SealStats stats;
  if (!(width > 0.0)) return stats;
  struct Face {
    std::uint32_t polygon;
    PlaneFrame frame;
  };
  std::map<std::tuple<long long, long long, long long, long long>, std::vector<Face>> planes;
  for (std::uint32_t i = 0; i < model.polygons.size(); ++i) {
    const model::Polygon& p = model.polygons[i];
    if (p.role != model::Role::Opaque) continue;
    PlaneFrame f;
    if (!plane_frame(p.vertices, f)) continue;
    bool planar = true;
    for (const auto& v : p.vertices) planar = planar && std::abs(f.distance(v)) <= kSealPlaneTolerance;
    if (!planar) continue;
    model::Vec3 n = f.normal;  // facing; the key keeps facings apart
    const auto key = std::make_tuple(std::llround(n.x * kNormalKey), std::llround(n.y * kNormalKey),
                                     std::llround(n.z * kNormalKey),
                                     std::llround(glm::dot(n, f.origin) / kSealPlaneTolerance));
    planes[key].push_back({i, f});
  }

  std::vector<model::Polygon> added;
  for (const auto& [key, faces] : planes) {
    if (faces.size() < 2) continue;
    ++stats.planes;
    // The first face's frame, with an exact axial frame for axial planes (projection then moves nothing).
    PlaneFrame frame = faces.front().frame;
    for (int a = 0; a < 3; ++a)
      if (std::abs(frame.normal[a]) == 1.0) {
        const double s = frame.normal[a];
        frame.u = frame.v = model::Vec3{0.0};
        frame.u[(a + 1) % 3] = 1.0;
        frame.v[(a + 2) % 3] = 1.0;
        if (s < 0.0) std::swap(frame.u, frame.v);  // (u, v, normal) right-handed
      }
    PointMap map(frame);
    ClipperLib::Clipper unite;
    std::vector<std::pair<glm::dvec2, glm::dvec2>> boxes;  // each face's 2D bounds, for the nearest face
    for (const Face& f : faces) {
      const model::Polygon& p = model.polygons[f.polygon];
      ClipperLib::Path outer = map.to_path(p.vertices);
      if (ClipperLib::Area(outer) < 0.0) ClipperLib::ReversePath(outer);
      unite.AddPath(outer, ClipperLib::ptSubject, true);
      for (const auto& h : p.holes) {
        ClipperLib::Path hole = map.to_path(h);
        if (ClipperLib::Area(hole) > 0.0) ClipperLib::ReversePath(hole);
        unite.AddPath(hole, ClipperLib::ptSubject, true);
      }
      glm::dvec2 lo(INFINITY), hi(-INFINITY);
      for (const auto& q : outer) {
        lo = glm::min(lo, from_int(q));
        hi = glm::max(hi, from_int(q));
      }
      boxes.push_back({lo, hi});
    }
    ClipperLib::Paths united;
    unite.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    const ClipperLib::Paths closed = close_region(united, 0.5 * width);
    ClipperLib::Clipper diff;
    diff.AddPaths(closed, ClipperLib::ptSubject, true);
    diff.AddPaths(united, ClipperLib::ptClip, true);
    ClipperLib::PolyTree slits;
    diff.Execute(ClipperLib::ctDifference, slits, ClipperLib::pftNonZero, ClipperLib::pftNonZero);

    for (const ClipperLib::PolyNode* node = slits.GetFirst(); node; node = node->GetNext()) {
      if (node->IsHole()) continue;
      double area = area_m2(node->Contour), edge = perimeter(node->Contour);
      for (const auto* h : node->Childs) {
        area += area_m2(h->Contour);  // negative for holes
        edge += perimeter(h->Contour);
      }
      if (area < kMinSlitArea || 2.0 * area / edge < kMinSlitWidth) continue;
      // The material, room and colour of the face nearest to the slit.
      const glm::dvec2 at = from_int(node->Contour.front());
      std::size_t nearest = 0;
      double best = INFINITY;
      for (std::size_t k = 0; k < boxes.size(); ++k) {
        const glm::dvec2 d = glm::max(glm::max(boxes[k].first - at, at - boxes[k].second), glm::dvec2(0.0));
        if (glm::length(d) < best) {
          best = glm::length(d);
          nearest = k;
        }
      }
      const model::Polygon& like = model.polygons[faces[nearest].polygon];
      ClipperLib::Paths slit{node->Contour};
      for (const auto* h : node->Childs) slit.push_back(h->Contour);
      ClipperLib::ClipperOffset grow;
      grow.AddPaths(offset_region(slit, -kSliver), ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
      ClipperLib::PolyTree fill;
      grow.Execute(fill, (kSliver + kSealOverlap) * kClipperScale);
      for (const ClipperLib::PolyNode* f = fill.GetFirst(); f; f = f->GetNext()) {
        if (f->IsHole()) continue;
        model::Polygon seal;
        for (const auto& q : f->Contour) seal.vertices.push_back(map.to_3d(q));
        for (const auto* h : f->Childs) {
          seal.holes.emplace_back();
          for (const auto& q : h->Contour) seal.holes.back().push_back(map.to_3d(q));
        }
        seal.material = like.material;
        seal.role = model::Role::Opaque;
        seal.group = like.group;
        seal.color = like.color;
        seal.name = "seal:" + like.name;
        seal.source_line = like.source_line;
        added.push_back(std::move(seal));
        ++stats.faces_added;
      }
      stats.area += area;
    }
  }
  for (auto& p : added) model.polygons.push_back(std::move(p));
  return stats;
}

}  // namespace walk::compiler
