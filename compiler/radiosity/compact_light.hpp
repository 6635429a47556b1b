#pragma once
// The paper's compact form of the light for display memory: per vertex one average colour (RGB, 8 bits each)
// and one 8-bit intensity per circuit, instead of a float RGB per circuit. Intensities are square-root
// encoded against a per-circuit scale, which spends the 256 steps where dim surfaces need them. What the
// compact form loses (each circuit's own tint, and quantisation) is measured, not assumed.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace walk::compiler {

struct CompactLight {
  std::vector<std::array<std::uint8_t, 4>> colour;  // per vertex, max channel 255 (alpha unused)
  std::vector<std::uint8_t> intensity;              // [vertex][circuit]
  std::vector<float> scale;                         // per circuit: intensity of code 255
  double rms_error_all_on = 0.0;   // RMS of the all-circuits-on radiosity error, in units of its mean
  double worst_circuit_rms = 0.0;  // largest per-circuit RMS error, each in units of that circuit's mean
};

// `light` is [vertex][circuit][3] radiosity.
[[nodiscard]] CompactLight compact_light(std::span<const float> light, std::size_t vertices,
                                         std::size_t circuits);

// The radiosity a display reconstructs from the compact form, [vertex][circuit][3].
[[nodiscard]] std::vector<float> expand_compact(const CompactLight& compact, std::size_t vertices,
                                                std::size_t circuits);

}  // namespace walk::compiler
