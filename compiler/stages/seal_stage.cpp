// seal: slits narrower than [model] seal between coplanar faces filled. After the openings, whose cut-outs
// are holes the seal must keep (they are far wider than a slit).
#include <spdlog/fmt/fmt.h>

#include "compiler/geometry/seal_gaps.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class SealStage final : public Stage {
 public:
  const char* name() const override { return "seal"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    if (!(s.config.seal_metres > 0.0)) return StageOutcome::skipped("scene seals no slits ([model] seal)");
    const std::size_t before = s.model.polygons.size();
    const SealStats c = seal_gaps(s.model, s.config.seal_metres);
    return StageOutcome::ran(before, s.model.polygons.size(),
                             fmt::format("width {} m: {}", s.config.seal_metres, c.summary()));
  }
};

}  // namespace

std::unique_ptr<Stage> seal_stage() {
  return std::make_unique<SealStage>();
}

}  // namespace walk::compiler
