#pragma once
// View-frustum culling on top of the PVS: each polygon's bounding box against the six planes of the
// view-projection matrix (Gribb & Hartmann). Conservative: a box is dropped only when it lies wholly outside
// one plane. Pure CPU.
#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"

namespace walk::render {

struct Box {
  std::array<float, 3> lo, hi;
};

// One box per polygon, from its vertices (empty polygons get an empty box that is always culled).
[[nodiscard]] std::vector<Box> polygon_boxes(std::span<const model::PolygonRecord> polygons,
                                             std::span<const model::VertexRecord> vertices);

// The ids among `candidates` whose boxes touch the frustum of `view_projection`.
[[nodiscard]] std::vector<std::uint32_t> in_frustum(const glm::mat4& view_projection,
                                                    std::span<const Box> boxes,
                                                    std::span<const std::uint32_t> candidates);

}  // namespace walk::render
