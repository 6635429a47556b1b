#pragma once
// Triangulates a convex integer polygon (counter-clockwise, possibly with collinear vertices) without
// degenerate triangles and without dropping any vertex, so neighbouring pieces meet without T-junctions.
#include <array>
#include <polyclipping/clipper.hpp>
#include <vector>

namespace walk::compiler {

// Appends counter-clockwise triangles, none degenerate, using every vertex, with the thinnest triangle as
// thick as possible. Falls back to a fan around one extra centre point when no such triangulation exists
// (a piece left slightly non-convex by rounding); triangles of non-positive area are then left out.
void fan_convex(const ClipperLib::Path& piece, std::vector<std::array<ClipperLib::IntPoint, 3>>& triangles);

// Twice the signed area of triangle abc in Clipper units squared (exact for |coordinates| < 2^30).
[[nodiscard]] double cross2(const ClipperLib::IntPoint& a, const ClipperLib::IntPoint& b,
                            const ClipperLib::IntPoint& c);

// True when the counter-clockwise path turns left or goes straight at every vertex.
[[nodiscard]] bool is_convex(const ClipperLib::Path& path);

}  // namespace walk::compiler
