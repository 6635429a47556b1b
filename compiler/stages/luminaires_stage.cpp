// luminaires: ceiling panels per room and the scene's explicit luminaires, grouped into circuits.
#include <spdlog/fmt/fmt.h>

#include "compiler/scene/luminaires.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class LuminairesStage final : public Stage {
 public:
  const char* name() const override { return "luminaires"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    const auto& config = s.config;
    if (!config.panels.enabled && config.luminaires.empty() && config.circuits.empty())
      return StageOutcome::skipped("scene adds no luminaires and regroups no circuits");
    const auto c = add_luminaires(s.model, config);
    return StageOutcome::ran(
        s.model.groups.size(), s.model.luminaires.size(),
        fmt::format("per-room {} explicit {} rooms without ceiling {} circuits {}", c.added_per_group,
                    c.explicit_panels, c.groups_without_ceiling, s.model.circuits.size()));
  }
};

}  // namespace

std::unique_ptr<Stage> luminaires_stage() {
  return std::make_unique<LuminairesStage>();
}

}  // namespace walk::compiler
