#pragma once
// The compile, in order. Each stage's entry point is one file in this folder (`<name>_stage.cpp`); the
// work itself lives in the folder of its subject (import/, cleanup/, geometry/, scene/, radiosity/, ...).
#include <memory>
#include <vector>

#include "compiler/stages/stage.hpp"

namespace walk::compiler {

[[nodiscard]] std::unique_ptr<Stage> import_stage();      // the model file -> polygons
[[nodiscard]] std::unique_ptr<Stage> rules_stage();       // [[rules]]: roles, materials, groups
[[nodiscard]] std::unique_ptr<Stage> cleanup_stage();     // strays, weld, degenerate faces
[[nodiscard]] std::unique_ptr<Stage> recentre_stage();    // a whole-metre local origin
[[nodiscard]] std::unique_ptr<Stage> openings_stage();    // doors and glass cut into their walls
[[nodiscard]] std::unique_ptr<Stage> seal_stage();        // slits between coplanar faces filled
[[nodiscard]] std::unique_ptr<Stage> luminaires_stage();  // panels and circuits
[[nodiscard]] std::unique_ptr<Stage> mesh_stage();        // polygons -> diced and coarse triangles
[[nodiscard]] std::unique_ptr<Stage> light_stage();       // radiosity or direct light per circuit
[[nodiscard]] std::unique_ptr<Stage> compact_stage();     // light per vertex -> colour + intensity
[[nodiscard]] std::unique_ptr<Stage> meta_stage();        // exposure, materials, groups, circuits
[[nodiscard]] std::unique_ptr<Stage> cells_stage();       // cells, portals, PVS per cluster
[[nodiscard]] std::unique_ptr<Stage> lod_stage();         // simplified clusters for moving frames

[[nodiscard]] inline std::vector<std::unique_ptr<Stage>> compile_stages() {
  std::vector<std::unique_ptr<Stage>> list;
  for (auto make :
       {import_stage, rules_stage, cleanup_stage, recentre_stage, openings_stage, seal_stage,
        luminaires_stage, mesh_stage, light_stage, compact_stage, meta_stage, cells_stage, lod_stage})
    list.push_back(make());
  return list;
}

}  // namespace walk::compiler
