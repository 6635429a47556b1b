#include "devices/hid/report_layout.hpp"

#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace walk::devices {

std::size_t HidReportLayout::field(const std::string& name) const {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == name) return i;
  return npos;
}

std::string HidReportLayout::check() const {
  if (report_id && length < 1) return "length must include the report id byte";
  for (const auto& f : fields) {
    if (f.size != 1 && f.size != 2 && f.size != 4)
      return fmt::format("field '{}': size {} (must be 1, 2 or 4 bytes)", f.name, f.size);
    if (f.offset + f.size > length)
      return fmt::format("field '{}': bytes {}..{} lie past the report length {}", f.name, f.offset,
                         f.offset + f.size - 1, length);
    if (report_id && f.offset == 0) return fmt::format("field '{}': offset 0 is the report id byte", f.name);
    if (!(f.min <= f.max)) return fmt::format("field '{}': min is above max", f.name);
    if (!std::isfinite(f.scale) || f.scale == 0.0)
      return fmt::format("field '{}': scale must be non-zero", f.name);
  }
  return {};
}

HidDecoded decode_report(const HidReportLayout& layout, std::span<const std::uint8_t> report) {
  HidDecoded out;
  if (layout.report_id && (report.empty() || report[0] != *layout.report_id)) {
    out.status = report.empty() ? HidDecode::Truncated : HidDecode::OtherReport;
    out.why = report.empty() ? "empty report"
                             : fmt::format("report id {} (expected {})", report[0], *layout.report_id);
    return out;
  }
  if (report.size() < layout.length) {
    out.status = HidDecode::Truncated;
    out.why = fmt::format("report of {} bytes, the layout needs {}", report.size(), layout.length);
    return out;
  }
  out.values.reserve(layout.fields.size());
  for (const auto& f : layout.fields) {
    std::uint32_t raw = 0;
    for (std::size_t i = 0; i < f.size; ++i) {
      const std::size_t byte = f.big_endian ? f.offset + i : f.offset + f.size - 1 - i;
      raw = (raw << 8) | report[byte];
    }
    double v;
    if (f.is_signed) {
      const unsigned bits = static_cast<unsigned>(f.size * 8);
      const std::int64_t wide = bits == 32
                                    ? static_cast<std::int64_t>(static_cast<std::int32_t>(raw))
                                    : (static_cast<std::int64_t>(raw) ^ (std::int64_t{1} << (bits - 1))) -
                                          (std::int64_t{1} << (bits - 1));
      v = static_cast<double>(wide);
    } else {
      v = static_cast<double>(raw);
    }
    v = v * f.scale + f.bias;
    if (!(v >= f.min && v <= f.max)) {
      out.status = HidDecode::OutOfRange;
      out.why = fmt::format("field '{}' = {:g} is outside {:g}..{:g}", f.name, v, f.min, f.max);
      out.values.clear();
      return out;
    }
    out.values.push_back(v);
  }
  return out;
}

}  // namespace walk::devices
