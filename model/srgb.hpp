#pragma once
// The sRGB transfer curve (IEC 61966-2-1) between 8-bit display codes and linear light (0..1), shared by
// the compiler (albedo maps' means and halving) and the renderer (accumulation, image error).
#include <array>
#include <cstdint>

namespace walk::model {

// Linear light of each 8-bit code.
[[nodiscard]] const std::array<double, 256>& srgb_decode_table();
// The nearest 8-bit code of a linear value, clamped to 0..1 first.
[[nodiscard]] std::uint8_t srgb_encode_byte(double linear);

}  // namespace walk::model
