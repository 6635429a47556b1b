#pragma once
// Geometry of single DXF entities, in world coordinates of the drawing (or block) that holds them: faces of
// 3DFACE, SOLID/TRACE, polyface and polygon meshes, and the sides that thickness extrudes from LINE, ARC,
// CIRCLE, LWPOLYLINE and 2D POLYLINE along their OCS normal (the DXF arbitrary-axis algorithm). Entities
// without thickness contribute wires (line segments), which 2D floor plans are made of.
#include <array>
#include <glm/mat3x3.hpp>
#include <string>
#include <vector>

#include "compiler/import/dxf_document.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Segments per full circle when arcs, circles and bulges are turned into straight pieces: 32 keeps the
// chord within 0.5% of the radius (5 mm on a 1 m column), below what a walkthrough display can show.
inline constexpr int kDxfSegmentsPerCircle = 32;

struct DxfShape {
  std::vector<std::vector<model::Vec3>>
      faces;  // counter-clockwise about their normal, as the file orders them
  std::vector<std::array<model::Vec3, 2>> wires;
  std::size_t degenerate = 0;  // faces with fewer than three distinct corners, dropped
  bool known = true;           // false: an entity type with no geometry we read (TEXT, HATCH...)
};

// Columns: OCS x, y and z (the unit normal) in world coordinates, by the arbitrary-axis algorithm.
[[nodiscard]] glm::dmat3 dxf_ocs(const model::Vec3& normal);

// Appends the entity's geometry to `out`. Throws walk::Error naming `file` and a line for malformed values.
void dxf_entity_shape(const DxfEntity& entity, const std::string& file, DxfShape& out);

}  // namespace walk::compiler
