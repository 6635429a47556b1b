#include "render/draw_list.hpp"

#include <algorithm>
#include <numeric>

#include "model/model.hpp"

namespace walk::render {

bool is_drawn(std::uint32_t role) {
  return role != std::uint32_t(model::Role::Opening) && role != std::uint32_t(model::Role::Ignored);
}

DrawList build_draw_list(std::span<const model::PolygonRecord> polygons,
                         std::span<const std::uint32_t> polygon_ids) {
  std::vector<std::uint32_t> ids(polygon_ids.begin(), polygon_ids.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

  struct Range {
    std::uint64_t first, count;
  };
  std::vector<Range> opaque, glass;
  DrawList list;
  for (std::uint32_t id : ids) {
    if (id >= polygons.size()) continue;
    const auto& p = polygons[id];
    if (!is_drawn(p.role) || p.index_count == 0) continue;
    ++list.polygons;
    list.triangles += p.index_count / 3;
    (p.role == std::uint32_t(model::Role::Glass) ? glass : opaque).push_back({p.first_index, p.index_count});
  }
  // Polygons are usually stored in id order, but nothing requires it: sort by index position before merging.
  auto merge = [](std::vector<Range>& ranges, DrawBatch& batch) {
    std::sort(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) { return a.first < b.first; });
    std::uint64_t end = ~std::uint64_t(0);
    for (const Range& r : ranges) {
      if (!batch.counts.empty() && end == r.first) {
        batch.counts.back() += std::int32_t(r.count);
      } else {
        batch.counts.push_back(std::int32_t(r.count));
        batch.byte_offsets.push_back(std::uintptr_t(r.first * sizeof(std::uint32_t)));
      }
      end = r.first + r.count;
    }
  };
  merge(opaque, list.opaque);
  merge(glass, list.glass);
  return list;
}

DrawList build_draw_list_all(std::span<const model::PolygonRecord> polygons) {
  std::vector<std::uint32_t> ids(polygons.size());
  std::iota(ids.begin(), ids.end(), 0u);
  return build_draw_list(polygons, ids);
}

}  // namespace walk::render
