#pragma once
// The compact light form's 8-bit intensity code (LINT), shared by the compiler that writes it and the
// display that reads it: logarithmic, kCompactStops below the circuit's scale, 0 for none.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace walk::model {

// Code k >= 1 stands for 2^((k - 255) x kCompactStops / 254) of the scale, 0 for none. Equal ratios per step
// (4.5 %, so at most 2.2 % off anywhere over 16 stops) suit light, whose hot spots (lamps, panels) are
// thousands of times the walls they light: a square-root code spends its steps on the hot spot and leaves
// walls 8 % apart.
inline constexpr double kCompactStops = 16.0;

// The fraction of the circuit's scale a code stands for.
[[nodiscard]] inline double compact_intensity(std::uint8_t code) {
  return code == 0 ? 0.0 : std::exp2((double(code) - 255.0) * kCompactStops / 254.0);
}

// The code nearest (in ratio) to `fraction` of the scale, clamped to 1; below code 1, whichever of 0 and
// code 1 is nearer.
[[nodiscard]] inline std::uint8_t compact_code(double fraction) {
  if (!(fraction > 0.0)) return 0;
  const double k = 255.0 + std::log2(std::min(fraction, 1.0)) * 254.0 / kCompactStops;
  if (k >= 0.5) return static_cast<std::uint8_t>(std::lround(std::max(k, 1.0)));
  return fraction >= 0.5 * compact_intensity(1) ? 1 : 0;
}

}  // namespace walk::model
