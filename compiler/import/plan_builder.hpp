#pragma once
// A 2D floor plan to a 3D building. The plan's walls are closed outlines (LINE/LWPOLYLINE wires, both faces
// of each wall drawn); doorways are gaps between two wall ends ("jambs": short outline edges facing each
// other across the gap). Walls are extruded to `wall_height`; each doorway is closed above `door_height` by
// a lintel, gets a threshold (floor) and an Opening polygon on each face of the wall, which the openings
// stage cuts out; every region enclosed by walls and doorways is a room with a floor and a ceiling. Windows
// are placed where the scene config says, as glass ("window N") on both faces of the nearest wall plus the
// reveals between them ("reveal", "sill", "head").
#include <cstddef>
#include <string>
#include <vector>

#include "compiler/import/dxf_reader.hpp"
#include "compiler/scene/plan_options.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct PlanStats {
  std::size_t loops = 0;       // closed wall outlines found
  std::size_t open_wires = 0;  // wires not on any closed outline: ignored
  std::size_t jambs = 0;       // short outline edges that may end a wall
  std::size_t doorways = 0;
  std::size_t rooms = 0;
  std::size_t wall_faces = 0;
  std::size_t windows = 0;  // windows placed
  std::size_t windows_unplaced = 0;
  double wall_area = 0.0;   // square metres of wall footprint
  double floor_area = 0.0;  // square metres of room floors
};

// Throws walk::Error naming `file` when the plan has no closed wall outline or options are inconsistent.
[[nodiscard]] model::Model build_plan(const std::vector<DxfWire>& wires, const PlanOptions& options,
                                      const std::string& file, PlanStats* stats);

}  // namespace walk::compiler
