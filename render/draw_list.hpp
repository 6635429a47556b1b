#pragma once
// What one frame draws: index ranges for glMultiDrawElements, opaque and glass apart. Made per frame from
// clusters (cluster_layout.hpp). Pure CPU.
#include <cstdint>
#include <vector>

#include "model/bundle_format.hpp"

namespace walk::render {

// Index ranges for one glMultiDrawElements call.
struct DrawBatch {
  std::vector<std::int32_t> counts;          // indices per range
  std::vector<std::uintptr_t> byte_offsets;  // into the index buffer
  [[nodiscard]] bool empty() const { return counts.empty(); }
};

// Nearest-first drawing sorts runs of adjacent units, not single units, up to this many triangles a run.
// llvmpipe pays about 0.6 us a draw range: Sibenik's 3,900 clusters of 3 triangles each, sorted one by one
// into 3,815 ranges a frame, drew 1.1x slower than in the compiler's order (204 ranges). The depth order
// needs no finer grain than a few hundred triangles; a cluster larger than that is still its own run.
inline constexpr std::uint32_t kNearestFirstRunTriangles = 256;

// Glass is kept apart: it is drawn after everything opaque, blended, so rooms show through windows.
struct DrawList {
  DrawBatch opaque;
  DrawBatch glass;
  std::uint32_t polygons = 0;
  std::uint32_t triangles = 0;
  std::uint32_t triangles_behind_portals = 0;  // in the frustum, but shown by no portal of the eye's way
  std::uint32_t triangles_occluded = 0;        // shown by the portals, but hidden by the occlusion buffer
  std::vector<std::uint32_t> units;            // the units drawn, ascending (what else they carry follows)
};

// Whether a polygon of this role is drawn: openings are holes and ignored faces are not part of the scene.
[[nodiscard]] bool is_drawn(std::uint32_t role);

}  // namespace walk::render
