// compact: the light per vertex and circuit reduced to one colour and one intensity per circuit, the form the
// kiosk mixes live where it is within kCompactErrorLimit per circuit; the others are shown full. Which and
// why (each circuit's compact error) is printed.
#include <spdlog/fmt/fmt.h>

#include <algorithm>

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
    std::vector<std::uint8_t> glowing(out.vertices.size(), 0);  // luminaire panels
    for (const auto& [polygon, luminaire] : s.panel_polygons) {
      const auto& p = out.polygons[polygon];
      std::fill_n(glowing.begin() + p.first_vertex, p.vertex_count, std::uint8_t(1));
    }
    s.compact = choose_light_forms(out.light.view(), out.vertices.size(), circuits, glowing);
    out.compact_colour = s.compact.colour;
    out.compact_intensity = s.compact.intensity;
    // Which circuits are shown full, and why: each one's error in the compact form.
    std::string full;
    std::size_t compact = 0;
    for (std::size_t c = 0; c < circuits; ++c) {
      if (s.compact.compact[c]) {
        ++compact;
        continue;
      }
      if (!full.empty()) full += ", ";
      full += fmt::format("{} {:.1f}%", s.model.circuits[c].name, 100.0 * s.compact.circuit_rms[c]);
    }
    // In: the full form's bytes (LGHT, LGHR); out: what the display keeps (LCOL, LINT, LINR, and LGHT's
    // entries of the circuits shown full).
    std::size_t full_entries = 0;
    for (const auto& e : out.light.entries) full_entries += s.compact.compact[e.circuit] ? 0 : 1;
    return StageOutcome::ran(
        out.light.entries.size() * sizeof(model::LightEntry) + out.light.first.size() * 4,
        out.vertices.size() * 4 +
            (out.compact_intensity.codes.size() + out.compact_intensity.first.size()) * 4 +
            full_entries * sizeof(model::LightEntry),
        fmt::format(
            "{} of {} circuits compact (worst {:.2f}% RMS, limit {:.0f}%), shown error all on {:.2f}% "
            "RMS{}",
            compact, circuits, 100.0 * s.compact.worst_circuit_rms, 100.0 * kCompactErrorLimit,
            100.0 * s.compact.rms_error_all_on,
            full.empty() ? "" : "; full, compact would be off by: " + full));
  }
};

}  // namespace

std::unique_ptr<Stage> compact_stage() {
  return std::make_unique<CompactStage>();
}

}  // namespace walk::compiler
