#pragma once
// Cuts a polygonal region (Clipper output: simple outer contours and holes) into convex pieces by horizontal
// lines through every vertex: between two such lines the region is a row of trapezoids. Trapezoids stacked
// on the same segment are merged while the union stays convex, which removes most slab cuts that do not
// need to be there (and the slivers they would make). Every vertex lying on a piece's top or bottom edge is
// inserted in that edge, so pieces meet vertex to vertex (no T-junctions).
#include <polyclipping/clipper.hpp>
#include <vector>

namespace walk::compiler {

// `extra_cuts`: further horizontal lines (a lighting grid) that cut the region and are never merged across.
[[nodiscard]] ClipperLib::Paths convex_pieces(const ClipperLib::Paths& region,
                                              const std::vector<ClipperLib::cInt>& extra_cuts);

}  // namespace walk::compiler
