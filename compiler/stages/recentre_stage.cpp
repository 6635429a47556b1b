// recentre: a whole-metre local origin at the model's centre, so float rendering keeps sub-millimetre
// precision even for drawings placed far from the world origin (the bundle stores the origin in double).
#include <glm/common.hpp>

#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class RecentreStage final : public Stage {
 public:
  const char* name() const override { return "recentre"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    auto& model = s.model;
    model.origin = glm::round(bounds_of(model).centre());
    for (auto& p : model.polygons) {
      for (auto& v : p.vertices) v -= model.origin;
      for (auto& hole : p.holes)
        for (auto& v : hole) v -= model.origin;
      if (p.texture_map) p.texture_map->translate(-model.origin);
    }
    for (auto& solid : model.solids)
      for (auto& face : solid.faces)
        for (auto& v : face) v -= model.origin;
    for (auto& l : model.luminaires) l.position -= model.origin;  // imported lights move with the geometry
    const std::size_t items = model.polygons.size() + model.luminaires.size();
    return StageOutcome::ran(items, items);
  }
};

}  // namespace

std::unique_ptr<Stage> recentre_stage() {
  return std::make_unique<RecentreStage>();
}

}  // namespace walk::compiler
