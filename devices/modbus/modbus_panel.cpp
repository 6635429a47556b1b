#include "devices/modbus/modbus_panel.hpp"

#include <modbus/modbus.h>
#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <thread>

#include "devices/modbus/register_levels.hpp"
#include "model/error.hpp"

namespace walk::devices {
namespace {

constexpr int kMaxSpan = 125;  // registers per read request (Modbus limit)
constexpr std::size_t kKeptRoundTrips = 4096;

std::string describe(const ModbusPanelConfig& c) {
  return c.transport == ModbusPanelConfig::Transport::Tcp
             ? fmt::format("dimmer panel (modbus tcp {}:{} unit {})", c.host, c.port, c.slave)
             : fmt::format("dimmer panel (modbus rtu {} {} {}{}{} unit {})", c.device, c.baud, c.data_bits,
                           c.parity, c.stop_bits, c.slave);
}

}  // namespace

ModbusDimmerPanel::ModbusDimmerPanel(ModbusPanelConfig config, TimeFn clock)
    : config_(std::move(config)), clock_(std::move(clock)), faults_(describe(config_), config_.faults) {
  if (config_.registers.empty())
    throw Error(name() + ": no channel registers configured (registers = [...])");
  const auto [lo, hi] = std::minmax_element(config_.registers.begin(), config_.registers.end());
  first_ = *lo;
  span_ = *hi - *lo + 1;
  if (*lo < 0 || *hi > 0xffff) throw Error(name() + ": register addresses must be 0..65535");
}

ModbusDimmerPanel::~ModbusDimmerPanel() {
  thread_.stop();
  disconnect();
}

void ModbusDimmerPanel::start() {
  thread_.start([this] {
    const double t0 = clock_();
    step();
    // Hold the poll rate; a failed connect waits out its backoff in slices so a stop is quick.
    const double left = 1.0 / config_.poll_hz - (clock_() - t0);
    if (left > 0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
  });
}

bool ModbusDimmerPanel::connect(double now) {
  if (!faults_.may_reopen(now)) return false;
  const auto& c = config_;
  ctx_ = c.transport == ModbusPanelConfig::Transport::Tcp
             ? modbus_new_tcp(c.host.c_str(), c.port)
             : modbus_new_rtu(c.device.c_str(), c.baud, c.parity, c.data_bits, c.stop_bits);
  if (!ctx_) {
    faults_.down(now, std::string("cannot create the libmodbus context: ") + modbus_strerror(errno));
    return false;
  }
  modbus_set_slave(ctx_, c.slave);
  const auto usec = static_cast<std::uint32_t>(c.timeout * 1e6);
  modbus_set_response_timeout(ctx_, usec / 1000000, usec % 1000000);
  if (modbus_connect(ctx_) < 0) {
    const std::string why = modbus_strerror(errno);
    disconnect();
    faults_.down(now, "cannot connect: " + why +
                          (c.transport == ModbusPanelConfig::Transport::Tcp
                               ? " (is the panel powered and on the network?)"
                               : " (is the adapter plugged in, and is walkd in the dialout group?)"));
    return false;
  }
  return true;
}

void ModbusDimmerPanel::disconnect() {
  if (!ctx_) return;
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
}

bool ModbusDimmerPanel::step() {
  const double now = clock_();
  if (!ctx_ && !connect(now)) return false;
  const bool one_request = span_ <= kMaxSpan;
  std::vector<std::uint16_t> raw(one_request ? static_cast<std::size_t>(span_) : config_.registers.size());
  auto read = [&](int addr, int n, std::uint16_t* dest) {
    return config_.input_registers ? modbus_read_input_registers(ctx_, addr, n, dest)
                                   : modbus_read_registers(ctx_, addr, n, dest);
  };
  std::string why;
  int attempts = 0;
  for (int attempt = 0; attempt <= config_.retries; ++attempt) {
    ++attempts;
    const double t0 = monotonic_seconds();
    bool ok = true;
    if (one_request) {
      ok = read(first_, span_, raw.data()) == span_;
    } else {
      for (std::size_t i = 0; ok && i < config_.registers.size(); ++i)
        ok = read(config_.registers[i], 1, &raw[i]) == 1;
    }
    const double t1 = monotonic_seconds();
    if (!ok) {
      why = modbus_strerror(errno);
      if (errno == EBADF || errno == ECONNRESET || errno == EPIPE) break;  // the link is gone: reconnect
      modbus_flush(ctx_);  // drop a late answer to the failed request so it is not taken for the retry's
      continue;
    }
    DimmerReading r;
    r.time = clock_();
    RegisterLevels decoded =
        decode_register_levels(config_.registers, first_, one_request, raw, config_.full_scale);
    if (!decoded.garbage.empty()) {
      faults_.garbage(r.time, decoded.garbage);
      return false;  // keep the last good levels; the panel answers, so no reconnect
    }
    r.levels = std::move(decoded.levels);
    faults_.good(r.time);
    std::lock_guard lock(mutex_);
    latest_ = std::move(r);
    if (round_trips_.size() >= kKeptRoundTrips) round_trips_.erase(round_trips_.begin());
    round_trips_.push_back(one_request ? t1 - t0 : (t1 - t0) / static_cast<double>(config_.registers.size()));
    ++reads_;
    return true;
  }
  disconnect();
  faults_.down(clock_(), fmt::format("read failed {} of {} tries: {}", attempts, config_.retries + 1, why));
  return false;
}

std::optional<DimmerReading> ModbusDimmerPanel::poll(double) {
  std::lock_guard lock(mutex_);
  return latest_;
}

std::vector<double> ModbusDimmerPanel::round_trips() const {
  std::lock_guard lock(mutex_);
  return round_trips_;
}

std::uint64_t ModbusDimmerPanel::reads() const {
  std::lock_guard lock(mutex_);
  return reads_;
}

}  // namespace walk::devices
