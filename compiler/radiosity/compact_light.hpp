#pragma once
// The paper's compact form of the light for display memory: per vertex one average colour (RGB, 8 bits each)
// and one 8-bit intensity per circuit, instead of a float RGB per circuit. Intensities are coded
// logarithmically against a per-circuit scale (model/compact_code.hpp): the same relative step for the
// dim wall as for the lamp's hot spot. What the
// compact form loses (each circuit's own tint, and quantisation) is measured, not assumed, and a circuit
// it would misrepresent is shown from the full form instead (choose_light_forms).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "model/light_rows.hpp"

namespace walk::compiler {

// A circuit is kept compact when its own relative RMS error (RMS of the error over the RMS of its light) is
// at most this: the accuracy issue 26 asks of the light itself, so the display adds no more than that.
inline constexpr double kCompactErrorLimit = 0.05;

struct CompactLight {
  std::vector<std::array<std::uint8_t, 4>> colour;  // per vertex, max channel 255 (alpha unused)
  // Per vertex, the codes of the circuits shown compact that reach it (LINT). While choosing, every
  // circuit's code is kept per light entry in `entry_code` (the light rows' order), those left out too.
  model::CompactCodes intensity;
  std::vector<std::uint8_t> entry_code;
  std::vector<float> scale;           // per circuit: intensity of code 255; 0 if left out
  std::vector<std::uint8_t> compact;  // per circuit: 1 shown compact, 0 shown full
  // Per circuit, its relative RMS error in the compact form (RMS of the error over the RMS of its light):
  // for a circuit shown full, the error that ruled it out.
  std::vector<double> circuit_rms;
  double rms_error_all_on = 0.0;   // relative RMS error of the all-circuits-on radiosity as shown
  double worst_circuit_rms = 0.0;  // largest circuit_rms among the circuits shown compact
};

// `light` is the radiosity per vertex (a row each) and circuit. Every circuit compact, or those with
// `included[c]` != 0: the colour is the average of the included circuits only. Vertices with `glowing[v]` !=
// 0 (luminaire panels) are coded but left out of the errors: their exitance is the circuit's brightest light
// by far, shown white, and would swamp the error of the surfaces they light.
[[nodiscard]] CompactLight compact_light(const model::LightRowsView& light, std::size_t vertices,
                                         std::size_t circuits, std::span<const std::uint8_t> included = {},
                                         std::span<const std::uint8_t> glowing = {});

// The compact form over the circuits it represents within `limit`: circuits are left out worst first (each
// one left out lets the colour follow the others) until every circuit kept is within it; after 16 passes
// of O(light entries) each, the rest above the limit go out together.
[[nodiscard]] CompactLight choose_light_forms(const model::LightRowsView& light, std::size_t vertices,
                                              std::size_t circuits,
                                              std::span<const std::uint8_t> glowing = {},
                                              double limit = kCompactErrorLimit);

// The radiosity a display reconstructs, [vertex][circuit][3]: compact circuits from the compact form, the
// others from `light` (the full form) as they are.
[[nodiscard]] std::vector<float> expand_compact(const CompactLight& compact,
                                                const model::LightRowsView& light, std::size_t vertices,
                                                std::size_t circuits);

}  // namespace walk::compiler
