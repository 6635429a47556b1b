#include "tools/gen/floor_loops.hpp"

#include <algorithm>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "compiler/geometry/clipper_convert.hpp"

namespace walk::gen {

using glm::dvec2;

double loop_area(const Loop2& loop) {
  double a = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const dvec2 p = loop[i], q = loop[(i + 1) % loop.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

ClipperLib::Path to_path(const Loop2& loop) {
  ClipperLib::Path path;
  for (const dvec2& p : loop) path.push_back(compiler::to_int(p));
  return path;
}

Loop2 to_loop(const ClipperLib::Path& path) {
  Loop2 loop;
  for (const auto& p : path) loop.push_back(compiler::from_int(p));
  return loop;
}

Loop2 rect(dvec2 lo, dvec2 hi) {
  return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
}

// Even-odd over every loop: inside the outer boundary and outside its holes.
bool inside(const std::vector<Loop2>& loops, dvec2 p) {
  bool in = false;
  for (const Loop2& l : loops)
    for (std::size_t i = 0, j = l.size() - 1; i < l.size(); j = i++)
      if ((l[i].y > p.y) != (l[j].y > p.y) &&
          p.x < (l[j].x - l[i].x) * (p.y - l[i].y) / (l[j].y - l[i].y) + l[i].x)
        in = !in;
  return in;
}

// Does segment a-b pass through the open box (lo, hi)? Liang-Barsky clipping of the segment.
bool segment_enters_box(dvec2 a, dvec2 b, dvec2 lo, dvec2 hi) {
  double t0 = 0.0, t1 = 1.0;
  const dvec2 d = b - a;
  const double p[4] = {-d.x, d.x, -d.y, d.y};
  const double q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] <= 0.0) return false;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  return t0 < t1;
}

// A box lies in the room when its corners are inside and no edge of the room (outer or hole) enters it.
bool box_in_room(const std::vector<Loop2>& room, dvec2 lo, dvec2 hi) {
  for (const dvec2 c : {lo, dvec2(hi.x, lo.y), hi, dvec2(lo.x, hi.y)})
    if (!inside(room, c)) return false;
  for (const Loop2& l : room)
    for (std::size_t i = 0; i < l.size(); ++i)
      if (segment_enters_box(l[i], l[(i + 1) % l.size()], lo, hi)) return false;
  return true;
}

bool boxes_overlap(dvec2 alo, dvec2 ahi, dvec2 blo, dvec2 bhi) {
  return alo.x < bhi.x && blo.x < ahi.x && alo.y < bhi.y && blo.y < ahi.y;
}

// The point of the room farthest from its walls, on a 5 cm grid: where a ceiling panel is centred.
dvec2 room_centre(const std::vector<Loop2>& room) {
  dvec2 lo(1e300), hi(-1e300);
  for (const dvec2& p : room.front()) lo = glm::min(lo, p), hi = glm::max(hi, p);
  constexpr double kStep = 0.05;
  dvec2 best = (lo + hi) * 0.5;
  double best_d = -1.0;
  for (double y = lo.y + kStep / 2; y < hi.y; y += kStep)
    for (double x = lo.x + kStep / 2; x < hi.x; x += kStep) {
      const dvec2 p(x, y);
      if (!inside(room, p)) continue;
      double d = 1e300;
      for (const Loop2& l : room)
        for (std::size_t i = 0; i < l.size(); ++i) {
          const dvec2 a = l[i], b = l[(i + 1) % l.size()];
          const double t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
          d = std::min(d, glm::distance(p, a + t * (b - a)));
        }
      if (d > best_d) best_d = d, best = p;
    }
  return best;
}

// Splits a horizontal polygon with holes into polygons without (OBJ faces have none): each hole is cut
// through by a line across the polygon at its centre, and the halves are split again until none is left.
std::vector<Loop2> without_holes(const std::vector<Loop2>& loops) {
  std::vector<Loop2> done;
  std::vector<std::vector<Loop2>> todo{loops};
  while (!todo.empty()) {
    std::vector<Loop2> shape = std::move(todo.back());
    todo.pop_back();
    if (shape.size() == 1) {
      done.push_back(std::move(shape.front()));
      continue;
    }
    dvec2 lo(1e300), hi(-1e300), hlo(1e300), hhi(-1e300);
    for (const dvec2& p : shape[0]) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (const dvec2& p : shape[1]) hlo = glm::min(hlo, p), hhi = glm::max(hhi, p);
    const double cut = 0.5 * (hlo.x + hhi.x);
    for (const Loop2& half : {rect(lo - 1.0, {cut, hi.y + 1.0}), rect({cut, lo.y - 1.0}, hi + 1.0)}) {
      ClipperLib::Clipper c;
      for (const Loop2& l : shape) c.AddPath(to_path(l), ClipperLib::ptSubject, true);
      c.AddPath(to_path(half), ClipperLib::ptClip, true);
      ClipperLib::PolyTree tree;
      c.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftEvenOdd, ClipperLib::pftNonZero);
      for (ClipperLib::PolyNode* n = tree.GetFirst(); n; n = n->GetNext()) {
        if (n->IsHole()) continue;
        std::vector<Loop2> piece{to_loop(n->Contour)};
        for (const ClipperLib::PolyNode* h : n->Childs) piece.push_back(to_loop(h->Contour));
        todo.push_back(std::move(piece));
      }
    }
  }
  return done;
}

}  // namespace walk::gen
