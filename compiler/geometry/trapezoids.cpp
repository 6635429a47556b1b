#include "compiler/geometry/trapezoids.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "compiler/geometry/convex_fan.hpp"

namespace walk::compiler {
namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

struct Edge {
  IntPoint lo, hi;  // lo.Y < hi.Y
  // x where the edge meets height y (lo.Y <= y <= hi.Y), rounded; exact at the end points, and the same for
  // both slabs that share the line, since it depends on the edge and y only.
  [[nodiscard]] cInt x_at(cInt y) const {
    if (y == lo.Y) return lo.X;
    if (y == hi.Y) return hi.X;
    const long double t = static_cast<long double>(y - lo.Y) / static_cast<long double>(hi.Y - lo.Y);
    return static_cast<cInt>(
        std::llround(static_cast<double>(lo.X + t * static_cast<long double>(hi.X - lo.X))));
  }
  [[nodiscard]] double x_mid(cInt y0, cInt y1) const {
    const double y = 0.5 * (static_cast<double>(y0) + static_cast<double>(y1));
    return static_cast<double>(lo.X) + (y - static_cast<double>(lo.Y)) / static_cast<double>(hi.Y - lo.Y) *
                                           static_cast<double>(hi.X - lo.X);
  }
};

// A stack of trapezoids: its left and right sides as chains of points from bottom to top.
struct Piece {
  std::vector<IntPoint> left, right;
  bool alive = true;
};

// Counter-clockwise outline of a piece without extra points on its top and bottom edges.
Path outline(const Piece& p) {
  Path path;
  auto add = [&](const IntPoint& q) {
    if (path.empty() || !(path.back() == q)) path.push_back(q);
  };
  for (const auto& q : p.right) add(q);
  for (auto it = p.left.rbegin(); it != p.left.rend(); ++it) add(*it);
  while (path.size() > 1 && path.back() == path.front()) path.pop_back();
  return path;
}

}  // namespace

Paths convex_pieces(const Paths& region, const std::vector<cInt>& extra_cuts) {
  std::vector<Edge> edges;
  std::vector<cInt> ys;
  for (const auto& path : region) {
    for (std::size_t i = 0; i < path.size(); ++i) {
      const IntPoint& a = path[i];
      const IntPoint& b = path[(i + 1) % path.size()];
      ys.push_back(a.Y);
      if (a.Y == b.Y) continue;  // horizontal edges lie on cut lines
      edges.push_back(a.Y < b.Y ? Edge{a, b} : Edge{b, a});
    }
  }
  if (ys.empty()) return {};
  const cInt lo_y = *std::min_element(ys.begin(), ys.end());
  const cInt hi_y = *std::max_element(ys.begin(), ys.end());
  std::vector<bool> is_extra;
  {
    std::vector<cInt> all = ys;
    for (cInt y : extra_cuts) {
      if (y > lo_y && y < hi_y) all.push_back(y);
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    std::sort(ys.begin(), ys.end());
    for (cInt y : all) is_extra.push_back(!std::binary_search(ys.begin(), ys.end(), y));
    ys = std::move(all);
  }

  // Trapezoids per slab, left to right: crossing edges sorted by x at mid-height pair up (even-odd).
  std::vector<Piece> pieces;
  std::vector<std::vector<std::size_t>> slabs(ys.size() > 0 ? ys.size() - 1 : 0);
  for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
    const cInt y0 = ys[k], y1 = ys[k + 1];
    std::vector<std::pair<double, const Edge*>> crossing;
    for (const auto& e : edges) {
      if (e.lo.Y <= y0 && e.hi.Y >= y1) crossing.emplace_back(e.x_mid(y0, y1), &e);
    }
    std::sort(crossing.begin(), crossing.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i + 1 < crossing.size(); i += 2) {
      const Edge& l = *crossing[i].second;
      const Edge& r = *crossing[i + 1].second;
      Piece p;
      p.left = {{l.x_at(y0), y0}, {l.x_at(y1), y1}};
      p.right = {{r.x_at(y0), y0}, {r.x_at(y1), y1}};
      slabs[k].push_back(pieces.size());
      pieces.push_back(std::move(p));
    }
  }

  // Every point on each cut line that some piece has there: what other pieces' edges on the line must
  // include.
  std::map<cInt, std::vector<cInt>> on_line;
  for (const auto& p : pieces) {
    for (const auto* q : {&p.left.front(), &p.right.front(), &p.left.back(), &p.right.back()}) {
      on_line[q->Y].push_back(q->X);
    }
  }
  for (auto& [y, xs] : on_line) {
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  }
  const auto inner_points = [&](cInt y, cInt x0, cInt x1) {
    const auto& xs = on_line[y];
    return std::upper_bound(xs.begin(), xs.end(), x0) != std::lower_bound(xs.begin(), xs.end(), x1);
  };

  // How many pieces have a corner at each point: a point on a merged line that only the two merged pieces
  // used, on a straight side, is no longer needed (keeping it would force a sliver into the fan).
  std::map<std::pair<cInt, cInt>, int> uses;
  for (const auto& p : pieces) {
    std::vector<std::pair<cInt, cInt>> corners;
    for (const auto* q : {&p.left.front(), &p.right.front(), &p.left.back(), &p.right.back()}) {
      corners.emplace_back(q->X, q->Y);
    }
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    for (const auto& c : corners) ++uses[c];
  }
  const auto append_chain = [&](std::vector<IntPoint>& chain, const std::vector<IntPoint>& upper) {
    const IntPoint joint = chain.back();
    if (chain.size() >= 2 && upper.size() >= 2 && uses[{joint.X, joint.Y}] <= 2 &&
        cross2(chain[chain.size() - 2], joint, upper[1]) == 0.0) {
      chain.pop_back();
      chain.push_back(upper[1]);
    } else {
      chain.push_back(upper[1]);
    }
    chain.insert(chain.end(), upper.begin() + 2, upper.end());
  };

  // Merge a piece with the one above when they share exactly the same segment and the union is convex.
  for (std::size_t k = 0; k + 2 < ys.size(); ++k) {
    if (is_extra[k + 1]) continue;
    for (std::size_t id : slabs[k]) {
      Piece& below = pieces[id];
      if (!below.alive) continue;
      const IntPoint tl = below.left.back(), tr = below.right.back();
      if (inner_points(ys[k + 1], tl.X, tr.X)) continue;
      for (std::size_t& up : slabs[k + 1]) {
        Piece& above = pieces[up];
        if (!(above.left.front() == tl) || !(above.right.front() == tr)) continue;
        Piece merged = below;
        append_chain(merged.left, above.left);
        append_chain(merged.right, above.right);
        const Path path = outline(merged);
        if (path.size() >= 3 && ClipperLib::Orientation(path) && is_convex(path)) {
          below = std::move(merged);
          above.alive = false;
          up = id;  // the merged piece now also ends on the next line up
        }
        break;
      }
    }
  }

  Paths out;
  for (const auto& p : pieces) {
    if (!p.alive) continue;
    Path path;
    auto add = [&](const IntPoint& q) {
      if (path.empty() || !(path.back() == q)) path.push_back(q);
    };
    const auto& bottom = on_line[p.left.front().Y];
    for (auto it = std::upper_bound(bottom.begin(), bottom.end(), p.left.front().X);
         it != bottom.end() && *it < p.right.front().X; ++it) {
      add({*it, p.left.front().Y});
    }
    for (const auto& q : p.right) add(q);
    const auto& top = on_line[p.left.back().Y];
    auto it = std::lower_bound(top.begin(), top.end(), p.right.back().X);
    while (it != top.begin()) {
      --it;
      if (*it <= p.left.back().X) break;
      add({*it, p.left.back().Y});
    }
    for (auto l = p.left.rbegin(); l != p.left.rend(); ++l) add(*l);
    while (path.size() > 1 && path.back() == path.front()) path.pop_back();
    if (path.size() >= 3) out.push_back(std::move(path));
  }
  return out;
}

}  // namespace walk::compiler
