// openings: doors (Opening faces) and glass cut out of the walls they lie in.
#include <spdlog/fmt/fmt.h>

#include <algorithm>

#include "compiler/geometry/openings.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class OpeningsStage final : public Stage {
 public:
  const char* name() const override { return "openings"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    const bool needed = std::any_of(s.model.polygons.begin(), s.model.polygons.end(), [](const auto& p) {
      return p.role == model::Role::Opening || p.role == model::Role::Glass;
    });
    if (!needed) return StageOutcome::skipped("scene has no openings or glass");
    if (s.model.csg_merged) return StageOutcome::skipped("the importer's CSG left no face over another");
    const std::size_t before = s.model.polygons.size();
    auto c = cut_openings(s.model);
    s.frame_groups = std::move(c.frame_groups);
    return StageOutcome::ran(before, s.model.polygons.size(),
                             fmt::format("hosts cut {} openings {} glass {} unmatched {}", c.hosts_cut,
                                         c.openings_cut, c.glass_cut, c.unmatched));
  }
};

}  // namespace

std::unique_ptr<Stage> openings_stage() {
  return std::make_unique<OpeningsStage>();
}

}  // namespace walk::compiler
