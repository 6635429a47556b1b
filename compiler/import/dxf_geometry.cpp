#include "compiler/import/dxf_geometry.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "compiler/import/dxf_tokenizer.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;

// The arbitrary-axis algorithm's threshold (DXF reference: "1/64"): normals this close to the world z axis
// take the world y axis to build OCS x.
constexpr double kArbitraryAxisLimit = 1.0 / 64.0;
// A bulge below this (tan of a quarter of the arc angle) is a straight segment: an arc that bows out by less
// than 1e-9 of its chord.
constexpr double kStraightBulge = 1e-9;
// Most corners a single polyline or mesh may produce: a bound for hostile files (a real building's largest
// polyline has thousands), so a fuzzed vertex count cannot exhaust memory.
constexpr std::size_t kMaxEntityCorners = 10'000'000;

class Fields {
 public:
  Fields(const DxfEntity& e, const std::string& file) : e_(e), file_(file) {}
  [[nodiscard]] double num(int code, double fallback) const {
    const DxfPair* p = e_.find(code);
    return p ? dxf_number(*p, file_) : fallback;
  }
  [[nodiscard]] int integer(int code, int fallback) const {
    const DxfPair* p = e_.find(code);
    return p ? dxf_integer(*p, file_) : fallback;
  }
  [[nodiscard]] bool has(int code) const { return e_.find(code) != nullptr; }
  [[nodiscard]] Vec3 point(int code, Vec3 fallback = Vec3(0.0)) const {
    return {num(code, fallback.x), num(code + 10, fallback.y), num(code + 20, fallback.z)};
  }
  [[nodiscard]] Vec3 normal() const {
    const Vec3 n = point(210, {0.0, 0.0, 1.0});
    const double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) {
      const DxfPair* p = e_.find(210);
      throw Error(located(file_, p ? p->code_line : e_.line, e_.type + " has a zero extrusion direction",
                          "set group codes 210/220/230 to a non-zero vector or delete them"));
    }
    return n / len;
  }

 private:
  const DxfEntity& e_;
  const std::string& file_;
};

[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw Error(located(file, line, what, "fix or delete this entity in the DXF file"));
}

// Extrudes the path `points` (world coordinates) by `offset`: one quad per segment, or wires when offset is
// 0.
void extrude(const std::vector<Vec3>& points, bool closed, const Vec3& offset, DxfShape& out) {
  const std::size_t n = points.size();
  const std::size_t segments = closed ? n : (n == 0 ? 0 : n - 1);
  const bool thick = glm::dot(offset, offset) > 0.0;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[(i + 1) % n];
    if (thick)
      out.faces.push_back({a, b, b + offset, a + offset});
    else
      out.wires.push_back({a, b});
  }
}

// Points of an arc in its OCS plane (radians, counter-clockwise from `start` by `sweep`), excluding its end.
void arc_points(const glm::dvec2& centre, double radius, double start, double sweep, double z,
                std::vector<Vec3>& out, bool include_end) {
  const int steps = std::max(
      1, static_cast<int>(std::ceil(std::abs(sweep) / (2.0 * std::numbers::pi) * kDxfSegmentsPerCircle)));
  for (int i = 0; i < steps + (include_end ? 1 : 0); ++i) {
    const double a = start + sweep * i / steps;
    out.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a), z});
  }
}

struct PathVertex {
  Vec3 p{0.0};  // OCS
  double bulge = 0.0;
};

// OCS path with bulges to straight points (OCS), each bulge arc replaced by chords.
std::vector<Vec3> flatten(const std::vector<PathVertex>& vertices, bool closed) {
  std::vector<Vec3> out;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const PathVertex& v = vertices[i];
    const bool has_next = closed || i + 1 < n;
    if (!has_next || std::abs(v.bulge) < kStraightBulge) {
      out.push_back(v.p);
      continue;
    }
    const Vec3& w = vertices[(i + 1) % n].p;
    const glm::dvec2 a(v.p), b(w);
    const double chord = glm::distance(a, b);
    if (!(chord > 0.0)) {
      out.push_back(v.p);
      continue;
    }
    const double sweep = 4.0 * std::atan(v.bulge);  // positive: counter-clockwise
    const double radius = chord / (2.0 * std::sin(std::abs(sweep) / 2.0));
    const glm::dvec2 mid = (a + b) * 0.5;
    const glm::dvec2 dir = (b - a) / chord;
    const glm::dvec2 left(-dir.y, dir.x);
    const double h = radius * std::cos(sweep / 2.0);  // centre distance from the chord, signed by bulge
    const glm::dvec2 centre = mid + left * (v.bulge > 0 ? h : -h);  // left of the chord for a CCW minor arc
    const double start = std::atan2(a.y - centre.y, a.x - centre.x);
    arc_points(centre, radius, start, sweep, v.p.z, out, false);
  }
  return out;
}

std::vector<Vec3> to_world(const glm::dmat3& ocs, const std::vector<Vec3>& points) {
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(ocs * p);
  return out;
}

void face_3d(const DxfEntity& e, const std::string& file, DxfShape& out) {
  const char* axes = "xyz";
  std::vector<Vec3> corners;
  for (int c = 0; c < 4; ++c) {
    int count = 0;
    Vec3 p{0.0};
    std::string missing;
    for (int a = 0; a < 3; ++a) {
      const int code = 10 * (a + 1) + c;
      if (const DxfPair* pair = e.find(code)) {
        p[a] = dxf_number(*pair, file);
        ++count;
      } else {
        missing +=
            std::string(missing.empty() ? "" : ", ") + axes[a] + " (group code " + std::to_string(code) + ")";
      }
    }
    if (count == 3) {
      corners.push_back(p);
      continue;
    }
    if (c == 3 && count == 0) break;  // a 3-corner 3DFACE: read as a triangle
    const std::string what = e.comment.empty() ? std::string("3DFACE") : "3DFACE \"" + e.comment + "\"";
    throw Error(
        located(file, e.line, what + " is missing corner " + std::to_string(c + 1) + " " + missing,
                "every 3DFACE needs corners 10/20/30 to 13/23/33; re-export the drawing or delete this "
                "entity"));
  }
  out.faces.push_back(std::move(corners));
}

void solid(const DxfEntity& e, const Fields& f, DxfShape& out) {
  const glm::dmat3 ocs = dxf_ocs(f.normal());
  // SOLID and TRACE list their corners in "Z" order: 1, 2, 4, 3 around the outline.
  const Vec3 c1 = f.point(10), c2 = f.point(11), c3 = f.point(12);
  const Vec3 c4 = f.has(13) ? f.point(13) : c3;
  const double elevation = f.num(38, c1.z);
  auto at = [&](Vec3 p) { return ocs * Vec3(p.x, p.y, elevation); };
  std::vector<Vec3> outline{at(c1), at(c2), at(c4), at(c3)};
  const Vec3 offset = ocs[2] * f.num(39, 0.0);
  if (glm::dot(offset, offset) > 0.0) {
    extrude(outline, true, offset, out);
    std::vector<Vec3> top;
    for (const Vec3& p : outline) top.push_back(p + offset);
    out.faces.push_back(std::move(top));
    out.faces.push_back({outline.rbegin(), outline.rend()});
  } else {
    out.faces.push_back(std::move(outline));
  }
}

void line(const Fields& f, DxfShape& out) {
  const Vec3 offset = f.normal() * f.num(39, 0.0);
  extrude({f.point(10), f.point(11)}, false, offset, out);
}

void arc_or_circle(const DxfEntity& e, const Fields& f, const std::string& file, DxfShape& out) {
  const glm::dmat3 ocs = dxf_ocs(f.normal());
  const Vec3 c = f.point(10);
  const double r = f.num(40, 0.0);
  if (!(r > 0.0)) fail(file, e.line, e.type + " has a radius of " + std::to_string(r) + ", not above 0");
  const bool circle = e.type == "CIRCLE";
  const double start = circle ? 0.0 : f.num(50, 0.0) * std::numbers::pi / 180.0;
  double sweep = 2.0 * std::numbers::pi;
  if (!circle) {
    sweep = f.num(51, 360.0) * std::numbers::pi / 180.0 - start;
    while (sweep <= 0.0) sweep += 2.0 * std::numbers::pi;
    sweep = std::min(sweep, 2.0 * std::numbers::pi);
  }
  std::vector<Vec3> points;
  arc_points(glm::dvec2(c), r, start, sweep, c.z, points, !circle);
  extrude(to_world(ocs, points), circle, ocs[2] * f.num(39, 0.0), out);
}

void lwpolyline(const DxfEntity& e, const Fields& f, const std::string& file, DxfShape& out) {
  const glm::dmat3 ocs = dxf_ocs(f.normal());
  const double elevation = f.num(38, 0.0);
  std::vector<PathVertex> vertices;
  for (const DxfPair& p : e.pairs) {
    if (p.code == 10) {
      if (vertices.size() >= kMaxEntityCorners) fail(file, p.code_line, "LWPOLYLINE has too many vertices");
      vertices.push_back({Vec3(dxf_number(p, file), 0.0, elevation), 0.0});
    } else if (p.code == 20 && !vertices.empty()) {
      vertices.back().p.y = dxf_number(p, file);
    } else if (p.code == 42 && !vertices.empty()) {
      vertices.back().bulge = dxf_number(p, file);
    }
  }
  const bool closed = (f.integer(70, 0) & 1) != 0;
  extrude(to_world(ocs, flatten(vertices, closed)), closed, ocs[2] * f.num(39, 0.0), out);
}

void polyface(const DxfEntity& e, const std::string& file, DxfShape& out) {
  std::vector<Vec3> positions;
  for (const DxfEntity& v : e.children) {
    if (v.type != "VERTEX") continue;
    const Fields vf(v, file);
    const int flags = vf.integer(70, 0);
    if ((flags & 128) && (flags & 64)) {
      positions.push_back(vf.point(10));
      continue;
    }
    if (!(flags & 128)) continue;
    std::vector<Vec3> corners;
    for (int code = 71; code <= 74; ++code) {
      const int index = std::abs(vf.integer(code, 0));  // negative: the edge after it is invisible
      if (index == 0) continue;
      if (static_cast<std::size_t>(index) > positions.size())
        fail(file, v.line,
             "polyface mesh face refers to vertex " + std::to_string(index) + " but only " +
                 std::to_string(positions.size()) + " vertices precede it");
      corners.push_back(positions[index - 1]);
    }
    if (corners.size() >= 3)
      out.faces.push_back(std::move(corners));
    else
      ++out.degenerate;
  }
}

void polygon_mesh(const DxfEntity& e, const Fields& f, const std::string& file, DxfShape& out) {
  const int flags = f.integer(70, 0);
  const long m = f.integer(71, 0), n = f.integer(72, 0);
  std::vector<Vec3> grid;
  for (const DxfEntity& v : e.children) {
    if (v.type != "VERTEX") continue;
    const Fields vf(v, file);
    if (vf.integer(70, 0) & 16) continue;  // spline frame control point, not on the surface
    grid.push_back(vf.point(10));
  }
  if (m < 2 || n < 2 || static_cast<std::size_t>(m) * static_cast<std::size_t>(n) != grid.size())
    fail(file, e.line,
         "polygon mesh of " + std::to_string(m) + " x " + std::to_string(n) + " vertices has " +
             std::to_string(grid.size()));
  const bool closed_m = flags & 1, closed_n = flags & 32;
  const long rows = closed_m ? m : m - 1, cols = closed_n ? n : n - 1;
  for (long i = 0; i < rows; ++i)
    for (long j = 0; j < cols; ++j) {
      const long i1 = (i + 1) % m, j1 = (j + 1) % n;
      out.faces.push_back({grid[i * n + j], grid[i * n + j1], grid[i1 * n + j1], grid[i1 * n + j]});
    }
}

void polyline(const DxfEntity& e, const Fields& f, const std::string& file, DxfShape& out) {
  const int flags = f.integer(70, 0);
  if (flags & 64) return polyface(e, file, out);
  if (flags & 16) return polygon_mesh(e, f, file, out);
  const bool closed = flags & 1;
  if (flags & 8) {  // 3D polyline: world coordinates, no thickness
    std::vector<Vec3> points;
    for (const DxfEntity& v : e.children)
      if (v.type == "VERTEX") points.push_back(Fields(v, file).point(10));
    extrude(points, closed, Vec3(0.0), out);
    return;
  }
  const glm::dmat3 ocs = dxf_ocs(f.normal());
  const double elevation = f.num(30, 0.0);
  std::vector<PathVertex> vertices;
  for (const DxfEntity& v : e.children) {
    if (v.type != "VERTEX") continue;
    const Fields vf(v, file);
    vertices.push_back({Vec3(vf.num(10, 0.0), vf.num(20, 0.0), elevation), vf.num(42, 0.0)});
  }
  extrude(to_world(ocs, flatten(vertices, closed)), closed, ocs[2] * f.num(39, 0.0), out);
}

}  // namespace

glm::dmat3 dxf_ocs(const Vec3& normal) {
  const Vec3 n = glm::normalize(normal);
  const Vec3 ax = (std::abs(n.x) < kArbitraryAxisLimit && std::abs(n.y) < kArbitraryAxisLimit)
                      ? glm::normalize(glm::cross(Vec3(0.0, 1.0, 0.0), n))
                      : glm::normalize(glm::cross(Vec3(0.0, 0.0, 1.0), n));
  const Vec3 ay = glm::normalize(glm::cross(n, ax));
  return glm::dmat3(ax, ay, n);
}

void dxf_entity_shape(const DxfEntity& e, const std::string& file, DxfShape& out) {
  const Fields f(e, file);
  if (e.type == "3DFACE")
    face_3d(e, file, out);
  else if (e.type == "SOLID" || e.type == "TRACE")
    solid(e, f, out);
  else if (e.type == "LINE")
    line(f, out);
  else if (e.type == "ARC" || e.type == "CIRCLE")
    arc_or_circle(e, f, file, out);
  else if (e.type == "LWPOLYLINE")
    lwpolyline(e, f, file, out);
  else if (e.type == "POLYLINE")
    polyline(e, f, file, out);
  else
    out.known = false;
}

}  // namespace walk::compiler
