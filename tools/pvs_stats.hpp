#pragma once
// What a bundle's PVS draws: triangles per cell on the walk, against the whole model (walk inspect,
// walk bench cells).
#include <algorithm>
#include <cstdint>

#include "model/bundle.hpp"

namespace walk::tools {

struct PvsTriangles {
  std::size_t walk_cells = 0;  // cells not flagged outside
  double average = 0.0;        // triangles a cell's PVS draws, averaged over walk cells
  std::uint64_t worst = 0;
  std::uint64_t total = 0;  // triangles in the model
};

inline PvsTriangles pvs_triangles(const model::Bundle& b) {
  PvsTriangles t;
  t.total = b.indices().size() / 3;
  std::uint64_t sum = 0;
  for (std::uint32_t c = 0; c < b.cells().size(); ++c) {
    if (b.cells()[c].flags & model::kCellOutside) continue;
    std::uint64_t n = 0;
    for (const auto p : b.cell_polygons(c)) n += b.polygons()[p].index_count / 3;
    sum += n;
    t.worst = std::max(t.worst, n);
    ++t.walk_cells;
  }
  t.average = t.walk_cells ? double(sum) / double(t.walk_cells) : 0.0;
  return t;
}

}  // namespace walk::tools
