#include "compiler/geometry/convex_fan.hpp"

#include <algorithm>
#include <cmath>

namespace walk::compiler {

double cross2(const ClipperLib::IntPoint& a, const ClipperLib::IntPoint& b, const ClipperLib::IntPoint& c) {
  // long double keeps products of coordinates up to ~2^31 exact enough for a sign test on x86-64.
  const long double abx = static_cast<long double>(b.X - a.X), aby = static_cast<long double>(b.Y - a.Y);
  const long double acx = static_cast<long double>(c.X - a.X), acy = static_cast<long double>(c.Y - a.Y);
  return static_cast<double>(abx * acy - aby * acx);
}

bool is_convex(const ClipperLib::Path& path) {
  const std::size_t n = path.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (cross2(path[(i + n - 1) % n], path[i], path[(i + 1) % n]) < 0.0) return false;
  }
  return true;
}

namespace {

// Pieces up to this many vertices get the best triangulation by dynamic programming (O(n^3)); slab pieces
// rarely have more than 8. Larger ones (long merged chains) get the best single fan (O(n^2)).
constexpr std::size_t kMaxOptimalVertices = 48;

// Triangle quality: its smallest altitude (twice the area over the longest side), in Clipper units; zero or
// negative for a degenerate or clockwise triangle. It measures how thin a sliver is.
double altitude(const ClipperLib::IntPoint& a, const ClipperLib::IntPoint& b, const ClipperLib::IntPoint& c) {
  const double twice = cross2(a, b, c);
  if (twice <= 0.0) return twice;
  const auto length = [](const ClipperLib::IntPoint& p, const ClipperLib::IntPoint& q) {
    return std::hypot(static_cast<double>(q.X - p.X), static_cast<double>(q.Y - p.Y));
  };
  return twice / std::max({length(a, b), length(b, c), length(c, a)});
}

// Triangulation of a convex polygon maximising its thinnest triangle; false when every triangulation has a
// degenerate triangle.
bool optimal(const ClipperLib::Path& piece, std::vector<std::array<ClipperLib::IntPoint, 3>>& triangles) {
  const std::size_t n = piece.size();
  std::vector<double> best(n * n, 1e300);
  std::vector<std::size_t> split(n * n, 0);
  for (std::size_t gap = 2; gap < n; ++gap) {
    for (std::size_t i = 0; i + gap < n; ++i) {
      const std::size_t j = i + gap;
      double value = -1e300;
      for (std::size_t k = i + 1; k < j; ++k) {
        const double q = std::min({altitude(piece[i], piece[k], piece[j]), best[i * n + k], best[k * n + j]});
        if (q > value) {
          value = q;
          split[i * n + j] = k;
        }
      }
      best[i * n + j] = value;
    }
  }
  if (!(best[n - 1] > 0.0)) return false;
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, n - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2) continue;
    const std::size_t k = split[i * n + j];
    triangles.push_back({piece[i], piece[k], piece[j]});
    todo.emplace_back(i, k);
    todo.emplace_back(k, j);
  }
  return true;
}

// The fan from the vertex whose thinnest triangle is thickest; false when every fan has a degenerate one.
bool best_fan(const ClipperLib::Path& piece, std::vector<std::array<ClipperLib::IntPoint, 3>>& triangles) {
  const std::size_t n = piece.size();
  std::size_t best = n;
  double best_min = 0.0;
  for (std::size_t a = 0; a < n; ++a) {
    double smallest = 1e300;
    for (std::size_t k = 1; k + 1 < n && smallest > best_min; ++k) {
      smallest = std::min(smallest, altitude(piece[a], piece[(a + k) % n], piece[(a + k + 1) % n]));
    }
    if (smallest > best_min) {
      best_min = smallest;
      best = a;
    }
  }
  if (best == n) return false;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    triangles.push_back({piece[best], piece[(best + k) % n], piece[(best + k + 1) % n]});
  }
  return true;
}

}  // namespace

void fan_convex(const ClipperLib::Path& piece, std::vector<std::array<ClipperLib::IntPoint, 3>>& triangles) {
  const std::size_t n = piece.size();
  if (n < 3) return;
  // Every triangle must have positive area, so that no vertex is skipped (no T-junction with the piece next
  // door); among such triangulations prefer the one without thin slivers, e.g. along a 3 mm strip of wall
  // left above a door a fan from one corner would make needles 0.1 mm thick.
  if (n <= kMaxOptimalVertices ? optimal(piece, triangles) : best_fan(piece, triangles)) return;
  // No valid triangulation without an extra point (or the piece is not quite convex after rounding): fan
  // around the centre, leaving out anything degenerate.
  long double sx = 0.0L, sy = 0.0L;
  for (const auto& p : piece) {
    sx += static_cast<long double>(p.X);
    sy += static_cast<long double>(p.Y);
  }
  const ClipperLib::IntPoint centre{static_cast<ClipperLib::cInt>(std::llround(static_cast<double>(sx / n))),
                                    static_cast<ClipperLib::cInt>(std::llround(static_cast<double>(sy / n)))};
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = piece[i];
    const auto& c = piece[(i + 1) % n];
    if (cross2(centre, b, c) > 0.0) triangles.push_back({centre, b, c});
  }
}

}  // namespace walk::compiler
