#include "devices/modbus/register_levels.hpp"

#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace walk::devices {

RegisterLevels decode_register_levels(std::span<const int> registers, int first, bool spanned,
                                      std::span<const std::uint16_t> raw, double full_scale) {
  RegisterLevels out;
  if (!(full_scale > 0.0) || !std::isfinite(full_scale)) {
    out.garbage = fmt::format("full scale {:g} is not a positive number", full_scale);
    return out;
  }
  out.levels.resize(registers.size());
  for (std::size_t ch = 0; ch < registers.size(); ++ch) {
    const long long index =
        spanned ? static_cast<long long>(registers[ch]) - first : static_cast<long long>(ch);
    if (index < 0 || static_cast<unsigned long long>(index) >= raw.size()) {
      out.garbage = fmt::format("channel {} (register {}) lies outside the {} registers read", ch,
                                registers[ch], raw.size());
      out.levels.clear();
      return out;
    }
    const std::uint16_t v = raw[static_cast<std::size_t>(index)];
    if (v > full_scale) {
      out.garbage = fmt::format("channel {} (register {}) = {} is above full scale {:g}", ch, registers[ch],
                                v, full_scale);
      out.levels.clear();
      return out;
    }
    out.levels[ch] = v / full_scale;
  }
  return out;
}

}  // namespace walk::devices
