#pragma once
// Adds the scene's luminaires to the model: explicit panels from the config, and (when asked) one ceiling
// panel per room for models that come without any, then groups luminaires into circuits.
#include <cstddef>

#include "compiler/scene/scene_config.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct LuminaireStats {
  std::size_t added_per_group = 0;
  std::size_t groups_without_ceiling = 0;  // rooms where no ceiling was found above the floor
  std::size_t explicit_panels = 0;
};

LuminaireStats add_luminaires(model::Model& model, const SceneConfig& config);

}  // namespace walk::compiler
