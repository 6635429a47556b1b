#pragma once
// What one cell draws: its PVS turned into index ranges, with neighbouring ranges merged so a whole cell is
// a handful of glMultiDrawElements entries. Pure CPU, built once per cell and cached by the renderer.
#include <cstdint>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"

namespace walk::render {

// Index ranges for one glMultiDrawElements call.
struct DrawBatch {
  std::vector<std::int32_t> counts;          // indices per range
  std::vector<std::uintptr_t> byte_offsets;  // into the index buffer
  [[nodiscard]] bool empty() const { return counts.empty(); }
};

// Glass is kept apart: it is drawn after everything opaque, blended, so rooms show through windows.
struct DrawList {
  DrawBatch opaque;
  DrawBatch glass;
  std::uint32_t polygons = 0;
  std::uint32_t triangles = 0;
};

// Whether a polygon of this role is drawn: openings are holes and ignored faces are not part of the scene.
[[nodiscard]] bool is_drawn(std::uint32_t role);

// Ranges for the polygons listed in `polygon_ids` (duplicates and out-of-range ids are skipped).
[[nodiscard]] DrawList build_draw_list(std::span<const model::PolygonRecord> polygons,
                                       std::span<const std::uint32_t> polygon_ids);
// Ranges for every polygon: used when the bundle has no cells or the eye is outside all of them.
[[nodiscard]] DrawList build_draw_list_all(std::span<const model::PolygonRecord> polygons);

}  // namespace walk::render
