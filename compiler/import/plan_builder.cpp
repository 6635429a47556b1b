#include "compiler/import/plan_builder.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <polyclipping/clipper.hpp>

#include "compiler/geometry/clipper_convert.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using glm::dvec2;
using model::Vec3;

// Two jambs face each other when their outward normals are this close to opposite (cos of ~8 degrees):
// drawings are rarely exact, but a door's two jambs are parallel to the eye.
constexpr double kFacingCosine = 0.99;
// A doorway needs its two jambs to overlap by this fraction of the shorter one across the gap.
constexpr double kJambOverlap = 0.5;
// Wall footprint inside a candidate doorway beyond this (square metres) means the gap is not a doorway
// (something stands in it): 1 cm2 allows for round-off along its edges.
constexpr double kDoorwayClearArea = 1e-4;

struct Edge {
  dvec2 a, b;
  std::size_t contour = 0;
  [[nodiscard]] double length() const { return glm::distance(a, b); }
  [[nodiscard]] dvec2 dir() const { return (b - a) / length(); }
  // Solid on the left (Clipper orientation: outer counter-clockwise, holes clockwise): outward is right.
  [[nodiscard]] dvec2 normal() const {
    const dvec2 t = dir();
    return {t.y, -t.x};
  }
};

struct Doorway {
  dvec2 origin, t, n;  // jamb i's corner at s0, along-wall direction, across-gap direction
  double s0 = 0, s1 = 0, width = 0;
  [[nodiscard]] dvec2 at(double s, double w) const { return origin + t * s + n * w; }
};

IntPoint to_clip(dvec2 p) {
  return to_int(p);
}
dvec2 from_clip(const IntPoint& p) {
  return from_int(p);
}

Paths edges_to_loops(const std::vector<std::pair<dvec2, dvec2>>& segments, PlanStats& stats) {
  std::map<std::pair<ClipperLib::cInt, ClipperLib::cInt>, std::vector<std::size_t>> at;
  std::vector<std::array<IntPoint, 2>> ends;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const IntPoint a = to_clip(segments[i].first), b = to_clip(segments[i].second);
    ends.push_back({a, b});
    if (a == b) continue;
    at[{a.X, a.Y}].push_back(i);
    at[{b.X, b.Y}].push_back(i);
  }
  std::vector<bool> used(segments.size(), false);
  Paths loops;
  for (std::size_t first = 0; first < segments.size(); ++first) {
    if (used[first] || ends[first][0] == ends[first][1]) continue;
    Path path{ends[first][0]};
    std::vector<std::size_t> chain{first};
    used[first] = true;
    IntPoint cur = ends[first][1];
    bool closed = false;
    while (true) {
      if (cur == path.front()) {
        closed = true;
        break;
      }
      path.push_back(cur);
      std::optional<std::size_t> next;
      for (std::size_t e : at[{cur.X, cur.Y}])
        if (!used[e]) {
          next = e;
          break;
        }
      if (!next) break;
      used[*next] = true;
      chain.push_back(*next);
      cur = ends[*next][0] == cur ? ends[*next][1] : ends[*next][0];
    }
    if (closed && path.size() >= 3) {
      loops.push_back(std::move(path));
      ++stats.loops;
    } else {
      stats.open_wires += chain.size();
    }
  }
  return loops;
}

std::vector<Edge> edges_of(const Paths& paths) {
  std::vector<Edge> edges;
  for (std::size_t c = 0; c < paths.size(); ++c) {
    const Path& p = paths[c];
    for (std::size_t i = 0; i < p.size(); ++i) {
      Edge e{from_clip(p[i]), from_clip(p[(i + 1) % p.size()]), c};
      if (e.length() > 0.0) edges.push_back(e);
    }
  }
  return edges;
}

double overlap_area(const Paths& a, const Path& b) {
  ClipperLib::Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPath(b, ClipperLib::ptClip, true);
  Paths out;
  c.Execute(ClipperLib::ctIntersection, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  double area = 0.0;
  for (const auto& p : out) area += std::abs(area_m2(p));
  return area;
}

std::vector<Doorway> find_doorways(const std::vector<Edge>& edges, const Paths& walls, const PlanOptions& o,
                                   PlanStats& stats) {
  std::vector<std::size_t> jambs;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (edges[i].length() <= o.max_wall_thickness) jambs.push_back(i);
  stats.jambs = jambs.size();
  // Best partner of each jamb: the nearest facing jamb across a gap of door width.
  std::map<std::size_t, std::pair<std::size_t, double>> best;
  for (std::size_t i : jambs) {
    const Edge& e = edges[i];
    const dvec2 n = e.normal(), t = e.dir();
    for (std::size_t j : jambs) {
      if (i == j) continue;
      const Edge& f = edges[j];
      if (glm::dot(n, f.normal()) > -kFacingCosine) continue;
      const double gap = glm::dot((f.a + f.b) * 0.5 - (e.a + e.b) * 0.5, n);
      if (gap < o.min_door_width || gap > o.max_door_width) continue;
      const double fa = glm::dot(f.a - e.a, t), fb = glm::dot(f.b - e.a, t);
      const double lo = std::max(0.0, std::min(fa, fb)), hi = std::min(e.length(), std::max(fa, fb));
      if (hi - lo < kJambOverlap * std::min(e.length(), f.length())) continue;
      const auto it = best.find(i);
      if (it == best.end() || gap < it->second.second) best[i] = {j, gap};
    }
  }
  std::vector<Doorway> doors;
  for (const auto& [i, partner] : best) {
    const auto [j, gap] = partner;
    if (j < i) continue;  // each pair once
    const auto back = best.find(j);
    if (back == best.end() || back->second.first != i) continue;  // not mutual
    const Edge& e = edges[i];
    const Edge& f = edges[j];
    Doorway d;
    d.origin = e.a;
    d.t = e.dir();
    d.n = e.normal();
    const double fa = glm::dot(f.a - e.a, d.t), fb = glm::dot(f.b - e.a, d.t);
    d.s0 = std::max(0.0, std::min(fa, fb));
    d.s1 = std::min(e.length(), std::max(fa, fb));
    d.width = gap;
    // The gap must be clear of wall: test a slightly shrunk rectangle.
    const double m = 1e-3;
    const Path rect{to_clip(d.at(d.s0 + m, m)), to_clip(d.at(d.s1 - m, m)), to_clip(d.at(d.s1 - m, gap - m)),
                    to_clip(d.at(d.s0 + m, gap - m))};
    if (overlap_area(walls, rect) > kDoorwayClearArea) continue;
    doors.push_back(d);
  }
  return doors;
}

class Emitter {
 public:
  Emitter(model::Model& model, double z0, dvec2 origin) : model_(model), z0_(z0), origin_(origin) {}

  [[nodiscard]] Vec3 at(dvec2 p, double z) const { return {p.x + origin_.x, p.y + origin_.y, z0_ + z}; }

  // A vertical rectangle over the segment a->b from height lo to hi, facing right of a->b.
  void wall(dvec2 a, dvec2 b, double lo, double hi, const std::string& group, const std::string& name,
            model::Role role = model::Role::Opaque) {
    if (!(hi > lo) || glm::distance(a, b) <= 0.0) return;
    add({at(a, lo), at(b, lo), at(b, hi), at(a, hi)}, group, name, role);
  }

  void add(std::vector<Vec3> vertices, const std::string& group, const std::string& name,
           model::Role role = model::Role::Opaque) {
    model::Polygon p;
    p.vertices = std::move(vertices);
    add(std::move(p), group, name, role);
  }

  void add(model::Polygon p, const std::string& group, const std::string& name,
           model::Role role = model::Role::Opaque) {
    p.group = model_.group_index(group);
    p.name = name;
    p.role = role;
    model_.polygons.push_back(std::move(p));
  }

 private:
  model::Model& model_;
  double z0_;
  dvec2 origin_;
};

double point_segment_distance(dvec2 p, const Edge& e, double& s) {
  const dvec2 t = e.dir();
  s = std::clamp(glm::dot(p - e.a, t), 0.0, e.length());
  return glm::distance(p, e.a + t * s);
}

void place_window(const PlanWindow& w, dvec2 q, const std::vector<Edge>& edges, const PlanOptions& o,
                  Emitter& out, std::size_t index, PlanStats& stats) {
  std::optional<std::size_t> nearest;
  double best = 1e300, s = 0.0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    double si = 0.0;
    const double d = point_segment_distance(q, edges[i], si);
    if (d < best) {
      best = d;
      nearest = i;
      s = si;
    }
  }
  if (!nearest || best > o.max_wall_thickness) {
    ++stats.windows_unplaced;
    return;
  }
  const Edge& e = edges[*nearest];
  const dvec2 t = e.dir(), n = e.normal();
  const double s0 = s - w.width / 2, s1 = s + w.width / 2;
  // The wall's other face: a facing edge behind this one, within a wall thickness, covering the window.
  std::optional<double> depth;
  for (const Edge& f : edges) {
    if (glm::dot(n, f.normal()) > -kFacingCosine) continue;
    const double d = glm::dot(e.a - f.a, n);  // f lies behind e, inside the wall
    if (d <= 0.0 || d > o.max_wall_thickness) continue;
    const double fa = glm::dot(f.a - e.a, t), fb = glm::dot(f.b - e.a, t);
    if (std::min(fa, fb) > s0 || std::max(fa, fb) < s1) continue;
    if (!depth || d < *depth) depth = d;
  }
  if (s0 < 0.0 || s1 > e.length() || !depth || !(w.head > w.sill)) {
    ++stats.windows_unplaced;
    return;
  }
  const std::string name = "window " + std::to_string(index + 1);
  const dvec2 a = e.a + t * s0, b = e.a + t * s1;        // on this face
  const dvec2 a2 = a - n * *depth, b2 = b - n * *depth;  // on the other face
  out.wall(a, b, w.sill, w.head, name, name, model::Role::Glass);
  out.wall(b2, a2, w.sill, w.head, name, name, model::Role::Glass);
  // Reveals facing into the opening: sides, sill (up) and head (down).
  out.wall(a2, a, w.sill, w.head, name, "reveal");
  out.wall(b, b2, w.sill, w.head, name, "reveal");
  out.add({out.at(a2, w.sill), out.at(b2, w.sill), out.at(b, w.sill), out.at(a, w.sill)}, name, "sill");
  out.add({out.at(a, w.head), out.at(b, w.head), out.at(b2, w.head), out.at(a2, w.head)}, name, "head");
  ++stats.windows;
}

}  // namespace

model::Model build_plan(const std::vector<DxfWire>& wires, const PlanOptions& o, const std::string& file,
                        PlanStats* stats_out) {
  if (!(o.wall_height > 0.0) || !(o.door_height > 0.0) || o.door_height > o.wall_height)
    throw Error(located(file, 0, "plan heights are inconsistent: need 0 < door_height <= wall_height",
                        "fix [plan] in the scene config"));
  if (!(o.min_door_width >= 0.0) || !(o.max_door_width > o.min_door_width) || !(o.max_wall_thickness > 0.0))
    throw Error(located(file, 0, "plan door widths or wall thickness are inconsistent",
                        "need 0 <= min_door_width < max_door_width and max_wall_thickness > 0 in [plan]"));
  PlanStats stats;
  model::Bounds box;
  for (const auto& w : wires) {
    box.add(w.a);
    box.add(w.b);
  }
  if (box.empty())
    throw Error(located(file, 0, "the plan has no lines", "draw the walls as LINE or LWPOLYLINE outlines"));
  const dvec2 origin(std::floor(box.min.x), std::floor(box.min.y));  // Clipper works near 0: full precision
  std::vector<std::pair<dvec2, dvec2>> segments;
  for (const auto& w : wires) segments.emplace_back(dvec2(w.a) - origin, dvec2(w.b) - origin);
  const Paths loops = edges_to_loops(segments, stats);
  if (loops.empty())
    throw Error(located(file, wires.front().source_line, "the plan has no closed wall outline",
                        "walls must be drawn as closed outlines (both faces and their ends)"));

  ClipperLib::Clipper wall_union;
  wall_union.AddPaths(loops, ClipperLib::ptSubject, true);
  Paths walls;
  wall_union.Execute(ClipperLib::ctUnion, walls, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  ClipperLib::CleanPolygons(walls, 1.0);  // 1 um: drop duplicate and collinear points
  for (const auto& p : walls) stats.wall_area += area_m2(p);

  const std::vector<Edge> wall_edges = edges_of(walls);
  const std::vector<Doorway> doors = find_doorways(wall_edges, walls, o, stats);
  stats.doorways = doors.size();

  ClipperLib::Clipper closer;
  closer.AddPaths(walls, ClipperLib::ptSubject, true);
  for (const auto& d : doors) {
    Path rect{to_clip(d.at(d.s0, 0)), to_clip(d.at(d.s1, 0)), to_clip(d.at(d.s1, d.width)),
              to_clip(d.at(d.s0, d.width))};
    if (!ClipperLib::Orientation(rect)) ClipperLib::ReversePath(rect);
    closer.AddPath(rect, ClipperLib::ptClip, true);
  }
  ClipperLib::PolyTree tree;
  closer.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);

  model::Model model;
  model.materials.push_back({"default", {0.5, 0.5, 0.5}});
  const double z0 = box.min.z;
  Emitter out(model, z0, origin);
  // Walls: every contour of walls + doorways, full height; rooms: the holes, with floor and ceiling.
  std::size_t room = 0;
  std::map<const ClipperLib::PolyNode*, std::string> groups;  // parents come before their children
  for (ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext()) {
    Path contour = node->Contour;
    ClipperLib::CleanPolygon(contour, 1.0);
    std::string group = "exterior";
    if (!node->IsHole() && groups.count(node->Parent)) group = groups[node->Parent];  // a wall inside a room
    if (node->IsHole() && contour.size() >= 3) {
      const double area = std::abs(area_m2(contour));
      if (area >= o.min_room_area) {
        group = "room " + std::to_string(++room);
        stats.floor_area += area;
        model::Polygon floor, ceiling;
        for (const auto& p : contour) ceiling.vertices.push_back(out.at(from_clip(p), o.wall_height));
        for (auto it = contour.rbegin(); it != contour.rend(); ++it)
          floor.vertices.push_back(out.at(from_clip(*it), 0.0));
        for (const ClipperLib::PolyNode* island : node->Childs) {  // free-standing walls in the room
          std::vector<Vec3> up, down;
          for (const auto& p : island->Contour) down.push_back(out.at(from_clip(p), o.wall_height));
          for (auto it = island->Contour.rbegin(); it != island->Contour.rend(); ++it)
            up.push_back(out.at(from_clip(*it), 0.0));
          floor.holes.push_back(std::move(up));
          ceiling.holes.push_back(std::move(down));
          stats.floor_area -= std::abs(area_m2(island->Contour));
        }
        out.add(std::move(floor), group, "floor");
        out.add(std::move(ceiling), group, "ceiling");
      } else {
        group = "cavity";
      }
    }
    groups[node] = group;
    if (contour.size() < 3) continue;
    for (std::size_t i = 0; i < contour.size(); ++i) {
      out.wall(from_clip(contour[i]), from_clip(contour[(i + 1) % contour.size()]), 0.0, o.wall_height, group,
               "wall");
      ++stats.wall_faces;
    }
  }
  stats.rooms = room;
  // Doorways: jambs up to the door head, the lintel's underside, and an opening on each face of the wall.
  for (std::size_t k = 0; k < doors.size(); ++k) {
    const Doorway& d = doors[k];
    const std::string name = "doorway " + std::to_string(k + 1);
    out.wall(d.at(d.s0, 0), d.at(d.s1, 0), 0.0, o.door_height, name, "jamb");
    out.wall(d.at(d.s1, d.width), d.at(d.s0, d.width), 0.0, o.door_height, name, "jamb");
    // (t, n) turn clockwise seen from above, so this order faces down.
    out.add({out.at(d.at(d.s0, 0), o.door_height), out.at(d.at(d.s1, 0), o.door_height),
             out.at(d.at(d.s1, d.width), o.door_height), out.at(d.at(d.s0, d.width), o.door_height)},
            name, "lintel");
    out.add({out.at(d.at(d.s0, 0), 0.0), out.at(d.at(d.s0, d.width), 0.0), out.at(d.at(d.s1, d.width), 0.0),
             out.at(d.at(d.s1, 0), 0.0)},
            name, "threshold");  // the floor under the doorway, which no room's floor covers
    out.wall(d.at(d.s0, 0), d.at(d.s0, d.width), 0.0, o.door_height, name, name, model::Role::Opening);
    out.wall(d.at(d.s1, d.width), d.at(d.s1, 0), 0.0, o.door_height, name, name, model::Role::Opening);
  }
  // Windows on the faces of walls + doorways (the same contours the wall faces were made from).
  Paths closed;
  ClipperLib::PolyTreeToPaths(tree, closed);
  ClipperLib::CleanPolygons(closed, 1.0);
  const std::vector<Edge> faces = edges_of(closed);
  for (std::size_t i = 0; i < o.windows.size(); ++i)
    place_window(o.windows[i], dvec2(o.windows[i].at) - origin, faces, o, out, i, stats);
  if (stats_out) *stats_out = stats;
  return model;
}

}  // namespace walk::compiler
