#pragma once
// Dimmer levels from the raw registers a Modbus panel answered with: each channel's register divided by
// full scale. A value above full scale is garbage (random bytes, a panel mid-reconfiguration): the whole
// reading is refused with the channel named, and the panel keeps its last good levels. Pure: the fuzz
// target and the tests call it without a panel.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace walk::devices {

struct RegisterLevels {
  std::vector<double> levels;  // one per channel, 0..1, when `garbage` is empty
  std::string garbage;         // what was wrong, for the device's fault log
};

// `raw` holds either the contiguous span read from register `first` (`spanned`), or one value per channel.
[[nodiscard]] RegisterLevels decode_register_levels(std::span<const int> registers, int first, bool spanned,
                                                    std::span<const std::uint16_t> raw, double full_scale);

}  // namespace walk::devices
