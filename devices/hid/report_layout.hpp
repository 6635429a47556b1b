#pragma once
// A HID input report's layout, from config: which report id, how long, and where each value sits (byte
// offset, size, signedness, endianness, scale, bias, valid range). Offsets count from the first byte that
// hidapi returns, which is the report id when the device numbers its reports.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace walk::devices {

struct HidField {
  std::string name;        // e.g. "speed", "steering", "yaw", "pitch"
  std::size_t offset = 0;  // byte offset in the report
  std::size_t size = 1;    // 1, 2 or 4 bytes
  bool is_signed = false;
  bool big_endian = false;  // HID itself is little-endian; some vendor reports are not
  double scale = 1.0;       // value = raw * scale + bias, in metres/second or radians
  double bias = 0.0;
  double min = -1e300, max = 1e300;  // a decoded value outside is garbage (random bytes usually are)
};

struct HidReportLayout {
  std::optional<std::uint8_t> report_id;  // nothing: the device sends unnumbered reports
  std::size_t length = 0;                 // bytes a report must have at least
  std::vector<HidField> fields;

  // Index of a field, or npos.
  [[nodiscard]] std::size_t field(const std::string& name) const;
  // Empty when the layout is usable; otherwise what is wrong (a field past the end, a bad size...).
  [[nodiscard]] std::string check() const;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
};

enum class HidDecode { Ok, OtherReport, Truncated, OutOfRange };

struct HidDecoded {
  HidDecode status = HidDecode::Ok;
  std::vector<double> values;  // one per layout field, when Ok
  std::string why;             // when not Ok: for the device's fault log
};

// Decodes one raw report. OtherReport (a report id this layout does not describe) is not a fault: devices
// may send several report kinds.
[[nodiscard]] HidDecoded decode_report(const HidReportLayout& layout, std::span<const std::uint8_t> report);

}  // namespace walk::devices
