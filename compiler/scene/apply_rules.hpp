#pragma once
// Applies the scene's face rules: role and material per face, orientation fix, ignored faces dropped.
#include <array>
#include <cstddef>

#include "compiler/scene/scene_config.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct RuleStats {
  std::array<std::size_t, 5> per_role{};  // indexed by model::Role, after the rules
  std::size_t flipped = 0;
  std::size_t dropped = 0;  // Role::Ignored faces removed
};

RuleStats apply_rules(model::Model& model, const SceneConfig& config);

}  // namespace walk::compiler
