// compact: the light per vertex and circuit reduced to one colour and one intensity per circuit, the form the
// kiosk mixes live; the error it makes is measured and printed.
#include <spdlog/fmt/fmt.h>

#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class CompactStage final : public Stage {
 public:
  const char* name() const override { return "compact"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    auto& out = s.out;
    const std::size_t circuits = s.model.circuits.size();
    if (circuits == 0 || s.model.luminaires.empty()) return StageOutcome::skipped("no light to compact");
    s.compact = compact_light(out.light, out.vertices.size(), circuits);
    out.compact_colour = s.compact.colour;
    out.compact_intensity = s.compact.intensity;
    return StageOutcome::ran(
        out.light.size() * sizeof(float), s.compact.colour.size() * 4 + s.compact.intensity.size(),
        fmt::format("error all on {:.2f}% RMS, worst circuit {:.2f}% RMS", 100.0 * s.compact.rms_error_all_on,
                    100.0 * s.compact.worst_circuit_rms));
  }
};

}  // namespace

std::unique_ptr<Stage> compact_stage() {
  return std::make_unique<CompactStage>();
}

}  // namespace walk::compiler
