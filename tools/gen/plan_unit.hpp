#pragma once
// One storey of a shared floor plan, imported through the compiler's own import and rules stages (so the
// generated building has exactly the walls, doorways, windows and rooms `walk compile` finds in the plan),
// with the outline of its outer walls for composing storeys around a corridor.
#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace walk::gen {

struct PlanUnit {
  std::string name;    // the --plan name
  std::string source;  // the plan file read
  model::Model model;  // world metres, floor at z = 0; roles and materials from the plan's scene rules
  std::vector<glm::dvec2> outline;  // the outer face of the outer walls, counter-clockwise seen from above
  double storey_height = 0.0;       // floor to ceiling: the next storey's floor is this storey's ceiling
};

// Plans `walk gen building --plan` knows, in the order `--help` lists them.
[[nodiscard]] std::vector<std::string> plan_names();

// Imports plan `name` from `data_dir` (the shared data folder) using its scene config in `scenes_dir`
// (the repository's config/scenes). Throws walk::Error for an unknown plan (listing the known ones) or a
// plan whose files are missing or whose outer walls do not close.
[[nodiscard]] PlanUnit load_plan_unit(const std::string& name, const std::string& scenes_dir,
                                      const std::string& data_dir);

}  // namespace walk::gen
