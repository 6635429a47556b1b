#include "compiler/visibility/cover_index.hpp"

#include <algorithm>
#include <cmath>

namespace walk::compiler {
namespace {

// About this many boundary segments per grid cell, and at most this many cells a side.
constexpr double kSegmentsPerCell = 4.0;
constexpr int kMaxCellsPerSide = 128;

struct Point {
  double x, y;
};

// The part of convex polygon `p` (counter-clockwise) on the left of the directed line a->b moved left by
// `inset` (Sutherland-Hodgman, one half-plane).
std::vector<Point> clip_left(const std::vector<Point>& p, Point a, Point b, double inset) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len = std::hypot(dx, dy);
  std::vector<Point> out;
  if (!(len > 0.0)) return p;
  const auto side = [&](const Point& q) { return (dx * (q.y - a.y) - dy * (q.x - a.x)) / len - inset; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point& s = p[i];
    const Point& e = p[(i + 1) % p.size()];
    const double ds = side(s), de = side(e);
    if (ds >= 0.0) out.push_back(s);
    if ((ds >= 0.0) != (de >= 0.0)) {
      const double t = ds / (ds - de);
      out.push_back({s.x + (e.x - s.x) * t, s.y + (e.y - s.y) * t});
    }
  }
  return out;
}

// Does the segment meet the inside of convex polygon `p` (counter-clockwise) over some length?
bool crosses_inside(const std::vector<Point>& p, double ax, double ay, double bx, double by) {
  double t0 = 0.0, t1 = 1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point& s = p[i];
    const Point& e = p[(i + 1) % p.size()];
    const double ex = e.x - s.x, ey = e.y - s.y;
    // Inside is left of each edge: f(t) = cross(edge, point(t) - s) > 0.
    const double f0 = ex * (ay - s.y) - ey * (ax - s.x);
    const double f1 = ex * (by - s.y) - ey * (bx - s.x);
    if (f0 <= 0.0 && f1 <= 0.0) return false;
    if (f0 < 0.0) t0 = std::max(t0, f0 / (f0 - f1));
    if (f1 < 0.0) t1 = std::min(t1, f0 / (f0 - f1));
    if (!(t0 < t1)) return false;
  }
  return t1 - t0 > 1e-12;
}

}  // namespace

CoverIndex::CoverIndex(const ClipperLib::Paths& cover) : paths_(cover) {
  double xlo = INFINITY, ylo = INFINITY, xhi = -INFINITY, yhi = -INFINITY;
  for (const auto& path : paths_) {
    PathBounds b{{INT64_MAX, INT64_MAX}, {INT64_MIN, INT64_MIN}};
    for (std::size_t i = 0; i < path.size(); ++i) {
      const auto& a = path[i];
      const auto& c = path[(i + 1) % path.size()];
      segments_.push_back({double(a.X), double(a.Y), double(c.X), double(c.Y)});
      b.lo = {std::min(b.lo.X, a.X), std::min(b.lo.Y, a.Y)};
      b.hi = {std::max(b.hi.X, a.X), std::max(b.hi.Y, a.Y)};
    }
    path_bounds_.push_back(b);
    xlo = std::min(xlo, double(b.lo.X));
    ylo = std::min(ylo, double(b.lo.Y));
    xhi = std::max(xhi, double(b.hi.X));
    yhi = std::max(yhi, double(b.hi.Y));
  }
  if (segments_.empty()) return;
  const double w = std::max(xhi - xlo, 1.0), h = std::max(yhi - ylo, 1.0);
  const double cells = std::max(1.0, double(segments_.size()) / kSegmentsPerCell);
  cell_ = std::max({std::sqrt(w * h / cells), w / kMaxCellsPerSide, h / kMaxCellsPerSide});
  x0_ = xlo;
  y0_ = ylo;
  nx_ = std::clamp(int(w / cell_) + 1, 1, kMaxCellsPerSide + 1);
  ny_ = std::clamp(int(h / cell_) + 1, 1, kMaxCellsPerSide + 1);
  cells_.resize(std::size_t(nx_) * std::size_t(ny_));
  for (std::uint32_t s = 0; s < segments_.size(); ++s) {
    const Segment& g = segments_[s];
    for (int y = row(std::min(g.ay, g.by)); y <= row(std::max(g.ay, g.by)); ++y)
      for (int x = column(std::min(g.ax, g.bx)); x <= column(std::max(g.ax, g.bx)); ++x)
        cells_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)].push_back(s);
  }
}

int CoverIndex::column(double x) const {
  return std::clamp(int(std::floor((x - x0_) / cell_)), 0, nx_ - 1);
}

int CoverIndex::row(double y) const {
  return std::clamp(int(std::floor((y - y0_) / cell_)), 0, ny_ - 1);
}

int CoverIndex::winding(double x, double y) const {
  // Every segment crossing the ray to +x lies in this row of cells, at or right of x's column.
  int w = 0;
  const int r = row(y);
  std::vector<std::uint32_t> seen;
  for (int c = column(x); c < nx_; ++c)
    for (const auto s : cells_[std::size_t(r) * std::size_t(nx_) + std::size_t(c)]) {
      const Segment& g = segments_[s];
      // Half-open in y so a vertex on the ray counts once; only upward or downward crossings right of x.
      const bool up = g.ay <= y && g.by > y, down = g.by <= y && g.ay > y;
      if (!up && !down) continue;
      const double cx = g.ax + (y - g.ay) * (g.bx - g.ax) / (g.by - g.ay);
      if (cx <= x) continue;
      if (std::find(seen.begin(), seen.end(), s) != seen.end()) continue;
      seen.push_back(s);
      w += up ? 1 : -1;
    }
  return w;
}

bool CoverIndex::contains(const ClipperLib::Path& section, double inset) const {
  if (segments_.empty()) return false;
  std::vector<Point> g;
  for (const auto& q : section) g.push_back({double(q.X), double(q.Y)});
  for (std::size_t i = 0; i < section.size() && g.size() >= 3; ++i) {
    const auto& a = section[i];
    const auto& b = section[(i + 1) % section.size()];
    g = clip_left(g, {double(a.X), double(a.Y)}, {double(b.X), double(b.Y)}, inset);
  }
  if (g.size() < 3) return true;  // thinner than twice the inset
  double xlo = INFINITY, ylo = INFINITY, xhi = -INFINITY, yhi = -INFINITY, cx = 0.0, cy = 0.0;
  for (const auto& p : g) {
    xlo = std::min(xlo, p.x);
    ylo = std::min(ylo, p.y);
    xhi = std::max(xhi, p.x);
    yhi = std::max(yhi, p.y);
    cx += p.x;
    cy += p.y;
  }
  for (int y = row(ylo); y <= row(yhi); ++y)
    for (int x = column(xlo); x <= column(xhi); ++x)
      for (const auto s : cells_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)]) {
        const Segment& e = segments_[s];
        if (crosses_inside(g, e.ax, e.ay, e.bx, e.by)) return false;
      }
  // No boundary inside: the shrunk section is wholly in or wholly out.
  return winding(cx / double(g.size()), cy / double(g.size())) != 0;
}

void CoverIndex::paths_near(const ClipperLib::IntPoint& lo, const ClipperLib::IntPoint& hi,
                            ClipperLib::Paths& out) const {
  for (std::size_t i = 0; i < paths_.size(); ++i) {
    const PathBounds& b = path_bounds_[i];
    if (b.hi.X < lo.X || b.lo.X > hi.X || b.hi.Y < lo.Y || b.lo.Y > hi.Y) continue;
    out.push_back(paths_[i]);
  }
}

}  // namespace walk::compiler
