#pragma once
// Lays out the index buffers so that each cell's PVS is few contiguous ranges: the renderer merges
// neighbouring polygons' ranges into one multi-draw entry, so a cell whose polygons lie together costs a
// handful of entries instead of one per polygon. Polygon ids, vertices and light do not move; only where
// each polygon's triangles sit in INDX (and CIDX) changes.
#include <cstdint>

#include "model/bundle.hpp"

namespace walk::compiler {

struct DrawOrderCounts {
  std::uint64_t ranges_before = 0;  // summed over cells, opaque and glass apart, as the renderer merges
  std::uint64_t ranges_after = 0;
};

// Ranges the renderer would draw for every cell's PVS with the bundle as it is (cells on up to `threads`
// threads, 0: all cores).
[[nodiscard]] std::uint64_t count_draw_ranges(const model::BundleContents& bundle, unsigned threads = 0);

// Sorts polygons by the set of cells whose PVS holds them, in Gray-code order (glass last, as it is drawn
// apart; cells in tree order), and rewrites INDX and CIDX in that order. Needs out.cells and out.pvs filled.
// A cluster's polygons share its membership, so with clusters the keys are made per cluster.
DrawOrderCounts order_for_cells(model::BundleContents& out, unsigned threads = 0);

}  // namespace walk::compiler
