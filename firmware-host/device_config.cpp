#include "firmware-host/device_config.hpp"

#include <algorithm>
#include <filesystem>
#include <numbers>

namespace walk::kiosk {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

// Ranges are checked on what the file says; defaults computed from other keys (a Modbus panel's stale_after
// from its poll rate, retry_max from a larger retry_min) are fitted, not reported as the user's mistake.
devices::FaultPolicy faults(const TomlTable& s, devices::FaultPolicy p) {
  p.stale_after = s.raw().get("stale_after") ? s.number("stale_after", p.stale_after, 0.001, 3600.0)
                                             : std::clamp(p.stale_after, 0.001, 3600.0);
  p.retry_min = s.number("retry_min", p.retry_min, 0.0, 3600.0);
  p.retry_max = s.raw().get("retry_max") ? s.number("retry_max", p.retry_max, p.retry_min, 3600.0)
                                         : std::max(p.retry_max, p.retry_min);
  p.log_every = s.number("log_every", p.log_every, 0.0, 86400.0);
  return p;
}

std::uint8_t byte_value(const TomlTable& s, const std::string& key, int fallback) {
  return static_cast<std::uint8_t>(s.integer(key, fallback, 0, 255));
}

devices::HidField hid_field(const TomlTable& f) {
  f.only({"name", "offset", "size", "signed", "big_endian", "scale", "bias", "min", "max", "unit"});
  devices::HidField h;
  const auto name = f.string("name");
  if (!name) f.fail("", "missing key 'name' (speed, steering, yaw, pitch, x, y or z)");
  h.name = *name;
  h.offset = static_cast<std::size_t>(f.integer("offset", 0, 0, 4095));
  h.size = static_cast<std::size_t>(f.integer("size", 1, 1, 4));
  if (h.size == 3) f.fail("size", "must be 1, 2 or 4 bytes");
  h.is_signed = f.boolean("signed", false);
  h.big_endian = f.boolean("big_endian", false);
  const std::string unit = f.string("unit").value_or("si");
  if (unit != "si" && unit != "deg") f.fail("unit", "unknown unit '" + unit + "' (si or deg)");
  const double k = unit == "deg" ? kDegrees : 1.0;  // degrees in the file, radians inside
  h.scale = f.number("scale", 1.0, -1e9, 1e9) * k;
  h.bias = f.number("bias", 0.0, -1e9, 1e9) * k;
  h.min = f.number("min", -1e300, -1e300, 1e300) * k;
  h.max = f.number("max", 1e300, -1e300, 1e300) * k;
  return h;
}

devices::HidReportLayout hid_layout(const TomlTable& s) {
  s.only({"id", "length", "fields"});
  devices::HidReportLayout l;
  if (s.raw().get("id")) l.report_id = byte_value(s, "id", 0);
  if (!s.raw().get("length")) s.fail("", "missing key 'length' (bytes in the report, the id byte included)");
  l.length = static_cast<std::size_t>(s.integer("length", 0, 1, 4096));
  const toml::node* n = s.raw().get("fields");
  const toml::array* arr = n ? n->as_array() : nullptr;
  if (!arr || arr->empty()) s.fail("fields", "expected an array of field tables {name, offset, size, ...}");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table* t = arr->get(i)->as_table();
    if (!t) s.fail("fields", "every field must be a table {name = ..., offset = ..., ...}");
    l.fields.push_back(hid_field(TomlTable(*t, s.file(), s.key_path("fields[" + std::to_string(i) + "]"))));
  }
  if (const auto problem = l.check(); !problem.empty()) s.fail("", problem);
  return l;
}

}  // namespace

DeviceConfig read_device(const TomlTable& s, DeviceRole role, const std::string& dir) {
  DeviceConfig d;
  d.line = static_cast<int>(s.raw().source().begin.line);
  d.backend = s.string("backend").value_or("mock");

  if (d.backend == "mock") {
    s.only({"backend", "trace"});
    const auto trace = s.string("trace");
    if (!trace) s.fail("", "missing key 'trace' (the CSV file a mock device replays)");
    d.trace = (trace->empty() || std::filesystem::path(*trace).is_absolute())
                  ? *trace
                  : (std::filesystem::path(dir) / *trace).lexically_normal().string();
    return d;
  }
  if (d.backend == "hid") {
    if (role != DeviceRole::Treadmill && role != DeviceRole::HeadTracker)
      s.fail("backend", "hid serves treadmills and head trackers (dimmer panels: modbus, buttons: gpio)");
    s.only({"backend", "path", "vendor_id", "product_id", "serial", "read_timeout_ms", "report",
            "stale_after", "retry_min", "retry_max", "log_every"});
    auto& h = d.hid;
    h.path = s.string("path").value_or("");
    h.vendor_id = static_cast<std::uint16_t>(s.integer("vendor_id", 0, 0, 0xffff));
    h.product_id = static_cast<std::uint16_t>(s.integer("product_id", 0, 0, 0xffff));
    h.serial = s.string("serial").value_or("");
    if (h.path.empty() && (h.vendor_id == 0 || h.product_id == 0))
      s.fail("", "give 'path' (/dev/hidrawN) or 'vendor_id' and 'product_id'");
    h.read_timeout_ms = s.integer("read_timeout_ms", h.read_timeout_ms, 1, 1000);
    const auto report = s.table("report");
    if (!report) s.fail("", "missing table 'report' (the report layout: id, length, fields)");
    h.layout = hid_layout(*report);
    h.faults = faults(s, h.faults);
    return d;
  }
  if (d.backend == "gpio") {
    if (role == DeviceRole::Treadmill) {
      s.only({"backend", "chip", "line", "active_low", "metres_per_pulse", "debounce_ms", "stop_after",
              "stale_after", "retry_min", "retry_max", "log_every"});
      auto& e = d.encoder;
      const auto chip = s.string("chip");
      if (!chip) s.fail("", "missing key 'chip' (gpiochip0, a label or a number)");
      e.chip = *chip;
      e.line = static_cast<unsigned>(s.integer("line", -1, 0, 1023));
      if (!s.raw().get("line")) s.fail("", "missing key 'line' (the encoder's line offset on the chip)");
      e.active_low = s.boolean("active_low", e.active_low);
      e.metres_per_pulse = s.number("metres_per_pulse", e.metres_per_pulse, 1e-6, 10.0);
      e.debounce = s.number("debounce_ms", e.debounce * 1e3, 0.0, 1000.0) / 1e3;
      e.stop_after = s.number("stop_after", e.stop_after, 0.01, 60.0);
      e.faults = faults(s, e.faults);
      return d;
    }
    if (role == DeviceRole::Buttons) {
      s.only({"backend", "chip", "lines", "active_low", "debounce_ms", "stale_after", "retry_min",
              "retry_max", "log_every"});
      auto& b = d.buttons;
      const auto chip = s.string("chip");
      if (!chip) s.fail("", "missing key 'chip' (gpiochip0, a label or a number)");
      b.chip = *chip;
      b.active_low = s.boolean("active_low", b.active_low);
      b.debounce = s.number("debounce_ms", b.debounce * 1e3, 0.0, 1000.0) / 1e3;
      const auto lines = s.table("lines");
      if (!lines)
        s.fail("", "missing table 'lines' (e.g. lines = { return_to_start = 22, next_building = 23 })");
      for (const auto& [k, v] : lines->raw()) {
        const auto button = devices::parse_button(std::string(k.str()));
        if (!button) lines->fail(std::string(k.str()), "unknown button (return_to_start or next_building)");
        b.lines.emplace_back(*button,
                             static_cast<unsigned>(lines->integer(std::string(k.str()), 0, 0, 1023)));
      }
      b.faults = faults(s, b.faults);
      return d;
    }
    s.fail("backend", "gpio serves treadmills (belt encoder) and buttons");
  }
  if (d.backend == "modbus") {
    if (role != DeviceRole::DimmerPanel) s.fail("backend", "modbus serves dimmer panels");
    s.only({"backend",    "transport", "host",        "port",      "device",    "baud",       "parity",
            "data_bits",  "stop_bits", "unit_id",     "registers", "function",  "full_scale", "poll_hz",
            "timeout_ms", "retries",   "stale_after", "retry_min", "retry_max", "log_every"});
    auto& m = d.modbus;
    const std::string transport = s.string("transport").value_or("tcp");
    if (transport == "tcp") {
      m.transport = devices::ModbusPanelConfig::Transport::Tcp;
      m.host = s.string("host").value_or(m.host);
      m.port = s.integer("port", m.port, 1, 65535);
    } else if (transport == "rtu") {
      m.transport = devices::ModbusPanelConfig::Transport::Rtu;
      const auto dev = s.string("device");
      if (!dev) s.fail("", "missing key 'device' (the serial line, e.g. /dev/ttyUSB0)");
      m.device = *dev;
      m.baud = s.integer("baud", m.baud, 300, 4000000);
      const std::string parity = s.string("parity").value_or("E");
      if (parity != "N" && parity != "E" && parity != "O") s.fail("parity", "must be \"N\", \"E\" or \"O\"");
      m.parity = parity[0];
      m.data_bits = s.integer("data_bits", m.data_bits, 5, 8);
      m.stop_bits = s.integer("stop_bits", m.stop_bits, 1, 2);
    } else {
      s.fail("transport", "unknown transport '" + transport + "' (tcp or rtu)");
    }
    m.slave = s.integer("unit_id", m.slave, 0, 247);
    const toml::node* regs = s.raw().get("registers");
    const toml::array* arr = regs ? regs->as_array() : nullptr;
    if (!arr || arr->empty())
      s.fail("registers", "expected the register address of each channel, e.g. [0, 1, 2]");
    for (const auto& r : *arr) {
      if (!r.is_integer() || *r.value<long long>() < 0 || *r.value<long long>() > 65535)
        s.fail("registers", "register addresses are integers 0..65535");
      m.registers.push_back(static_cast<int>(*r.value<long long>()));
    }
    const std::string function = s.string("function").value_or("holding");
    if (function != "holding" && function != "input") s.fail("function", "must be \"holding\" or \"input\"");
    m.input_registers = function == "input";
    m.full_scale = s.number("full_scale", m.full_scale, 1.0, 65535.0);
    m.poll_hz = s.number("poll_hz", m.poll_hz, 0.1, 1000.0);
    m.timeout = s.number("timeout_ms", m.timeout * 1e3, 1.0, 60000.0) / 1e3;
    m.retries = s.integer("retries", m.retries, 0, 100);
    devices::FaultPolicy fp;
    fp.stale_after = 3.0 / m.poll_hz + m.timeout * (m.retries + 1);  // a few missed polls before "stale"
    m.faults = faults(s, fp);
    return d;
  }
  s.fail("backend", "unknown device backend '" + d.backend + "' (mock, hid, gpio or modbus)");
}

}  // namespace walk::kiosk
