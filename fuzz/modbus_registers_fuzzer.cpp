// libFuzzer target: dimmer levels decoded from the raw registers a Modbus panel answers with. The input's
// first bytes choose the channels' register addresses, the read's first register, whether it was one
// contiguous read, and full scale; the rest are the registers. Levels that decode must lie in 0..1.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "devices/modbus/register_levels.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  auto next = [&]() -> std::uint8_t { return at < size ? data[at++] : 0; };
  const std::uint8_t head = next();
  const bool spanned = head & 1;
  const int first = next() - 16;
  const double full_scale = (head & 2) ? double(next() | next() << 8) : 1000.0 - next();
  std::vector<int> registers(next() % 17);
  for (int& r : registers) r = next() - 8;
  std::vector<std::uint16_t> raw;
  while (at + 1 < size) raw.push_back(std::uint16_t(next() | next() << 8));
  const auto decoded = walk::devices::decode_register_levels(registers, first, spanned, raw, full_scale);
  if (decoded.garbage.empty()) {
    if (decoded.levels.size() != registers.size()) std::abort();
    for (double level : decoded.levels)
      if (!std::isfinite(level) || level < 0.0 || level > 1.0) std::abort();
  }
  return 0;
}
