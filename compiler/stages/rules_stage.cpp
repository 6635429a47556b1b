// rules: the scene's [[rules]] give each face its role (opaque, glass, opening, dropped), material and group.
#include <spdlog/fmt/fmt.h>

#include "compiler/scene/apply_rules.hpp"
#include "compiler/stages/stages.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

class RulesStage final : public Stage {
 public:
  const char* name() const override { return "rules"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    const auto r = apply_rules(s.model, s.config);
    if (!has_drawn_faces(s.model))
      throw Error(located(s.config.model_file, 0,
                          "empty model: no opaque or glass faces after the scene's rules",
                          "check the [[rules]] in " + s.config.path));
    return StageOutcome::ran(s.model.polygons.size() + r.dropped, s.model.polygons.size(),
                             fmt::format("opaque {} glass {} opening {} dropped {} flipped {}", r.per_role[0],
                                         r.per_role[1], r.per_role[2], r.dropped, r.flipped));
  }
};

}  // namespace

std::unique_ptr<Stage> rules_stage() {
  return std::make_unique<RulesStage>();
}

}  // namespace walk::compiler
