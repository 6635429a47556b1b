#pragma once
// Automatic exposure: the radiosity that a given share of the lit surfaces' area is darker than. Weighted by
// area, not counted by vertex: light refinement puts most of a mesh's vertices next to its lamps, and a
// percentile over vertices then reads the lamps' neighbourhood and darkens the whole picture (the house
// refined at 0.2 m: exposure 6.05 W/m2 by vertices, 2.2 shot at 0.4 m).
#include <span>

namespace walk::compiler {

// The smallest value v such that the values at or below v carry at least `share` (0..1) of the total
// weight. 0 when nothing has weight. `values` and `weights` pair up; weights below zero count as zero.
[[nodiscard]] double weighted_percentile(std::span<const double> values, std::span<const double> weights,
                                         double share);

}  // namespace walk::compiler
