#include "compiler/geometry/convex_fan.hpp"

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

void fan_convex(const ClipperLib::Path& piece, std::vector<std::array<ClipperLib::IntPoint, 3>>& triangles) {
  const std::size_t n = piece.size();
  if (n < 3) return;
  std::vector<bool> corner(n);
  for (std::size_t i = 0; i < n; ++i)
    corner[i] = cross2(piece[(i + n - 1) % n], piece[i], piece[(i + 1) % n]) > 0.0;
  // A fan from a corner whose two neighbours are corners too has no zero-area triangle: the only vertices
  // collinear with the apex would lie on its two edges, and those edges have no intermediate vertices.
  for (std::size_t a = 0; a < n; ++a) {
    if (!corner[a] || !corner[(a + 1) % n] || !corner[(a + n - 1) % n]) continue;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const auto& b = piece[(a + k) % n];
      const auto& c = piece[(a + k + 1) % n];
      if (cross2(piece[a], b, c) > 0.0) triangles.push_back({piece[a], b, c});
    }
    return;
  }
  // Otherwise fan around the centre (inside, as the piece is convex).
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
