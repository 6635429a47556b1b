#pragma once
// [plan] of a scene config: how a 2D floor plan becomes 3D (compiler/import/plan_builder.hpp builds it).
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct PlanWindow {
  model::Vec3 at{0.0};  // a point on or next to the wall, metres (z ignored)
  double width = 1.2;   // metres along the wall
  double sill = 0.9;    // metres above the floor
  double head = 2.1;
};

struct PlanOptions {
  double wall_height = 2.7;         // metres
  double door_height = 2.1;         // metres; below wall_height
  double min_door_width = 0.5;      // gaps narrower than this are not doorways (chases, drawing slop)
  double max_door_width = 2.0;      // gaps wider than this are open space, not doorways
  double max_wall_thickness = 0.5;  // a jamb (wall end) is an outline edge no longer than this
  double min_room_area = 0.25;      // square metres; smaller enclosed regions (wall cavities) get no floor
  std::vector<PlanWindow> windows;
};

}  // namespace walk::compiler
