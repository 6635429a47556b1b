#pragma once
// The import stage: reads the scene's model file in its format (DXF, 2D DXF plan, Quake .map, or a mesh
// through assimp) into a Model, and says what it read.
#include <cstddef>
#include <string>
#include <vector>

#include "compiler/scene/scene_config.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct ImportReport {
  std::string format;
  std::string detail;  // one line for the stage log: counts by entity/brush/mesh, what was skipped
  std::size_t faces = 0, openings = 0, luminaires = 0, circuits = 0;
  // Materials the file defined (true colours, textures, OBJ/glTF materials). import_model numbers them after
  // the scene config's materials, which the rules stage installs; append_imported_materials puts them back.
  std::vector<model::Material> materials;
};

// Throws walk::Error naming the file (and line, where the format has lines) on bad input.
[[nodiscard]] model::Model import_model(const SceneConfig& config, ImportReport* report);

// After the rules stage replaced model.materials by the config's: appends the imported ones again, so
// polygons that no rule gave a material keep the file's colour. Does nothing when they are still there.
void append_imported_materials(model::Model& model, const SceneConfig& config, const ImportReport& report);

}  // namespace walk::compiler
