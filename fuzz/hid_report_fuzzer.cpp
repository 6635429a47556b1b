// libFuzzer target: HID report layouts and the reports decoded with them. The input's first bytes describe
// a layout (report id, length, up to four fields with offset, size, signedness, endianness and valid range);
// a layout that check() accepts then decodes the rest of the input as a report. A decoded value must be
// finite and inside its field's range; anything else must come back as a status, never a crash.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "devices/hid/report_layout.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  auto next = [&]() -> std::uint8_t { return at < size ? data[at++] : 0; };
  walk::devices::HidReportLayout layout;
  const std::uint8_t head = next();
  if (head & 1) layout.report_id = next();
  layout.length = next() % 65;
  const int fields = head >> 1 & 3;
  for (int i = 0; i <= fields; ++i) {
    walk::devices::HidField f;
    f.name = "f" + std::to_string(i);
    f.offset = next() % 70;
    f.size = next() % 6;  // 0, 3 and 5 are invalid sizes check() must refuse
    const std::uint8_t flags = next();
    f.is_signed = flags & 1;
    f.big_endian = flags & 2;
    f.scale = (flags & 4) ? -0.001 * next() : 0.01 * next();
    f.bias = double(static_cast<std::int8_t>(next()));
    if (flags & 8) {
      f.min = -double(next());
      f.max = double(next());
    }
    layout.fields.push_back(f);
  }
  if (!layout.check().empty()) return 0;
  const auto decoded = walk::devices::decode_report(layout, std::span(data + at, size - at));
  if (decoded.status == walk::devices::HidDecode::Ok) {
    if (decoded.values.size() != layout.fields.size()) std::abort();
    for (std::size_t i = 0; i < decoded.values.size(); ++i) {
      const double v = decoded.values[i];
      if (!std::isfinite(v) || v < layout.fields[i].min || v > layout.fields[i].max) {
        std::fprintf(stderr, "field %zu decoded to %g outside [%g, %g]\n", i, v, layout.fields[i].min,
                     layout.fields[i].max);
        std::abort();
      }
    }
  }
  return 0;
}
