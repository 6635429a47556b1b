#include "compiler/stages/stage.hpp"

#include <algorithm>

namespace walk::compiler {

const model::StageRecord* previous_record(const CompileState& state, const char* name) {
  if (!state.previous) return nullptr;
  for (const auto& s : state.previous->stages())
    if (state.previous->string(s.name) == name) return &s;
  return nullptr;
}

bool has_drawn_faces(const model::Model& model) {
  return std::any_of(model.polygons.begin(), model.polygons.end(),
                     [](const auto& p) { return drawn(p.role); });
}

}  // namespace walk::compiler
