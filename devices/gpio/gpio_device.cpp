#include "devices/gpio/gpio_device.hpp"

#include <spdlog/fmt/fmt.h>

namespace walk::devices {

GpioReader::GpioReader(std::string name, std::unique_ptr<GpioSource> source, FaultPolicy policy, TimeFn clock)
    : source_(std::move(source)), faults_(std::move(name), policy), clock_(std::move(clock)) {}

void GpioReader::start(std::function<void(const LineEvent&)> on_event, int timeout_ms) {
  thread_.start([this, on_event = std::move(on_event), timeout_ms] { step(on_event, timeout_ms); });
}

void GpioReader::step(const std::function<void(const LineEvent&)>& on_event, int timeout_ms) {
  const double now = clock_();
  const bool was_open = open_;
  if (!ensure_open(*source_, open_, faults_, now, thread_.running(), timeout_ms)) return;
  if (!was_open) faults_.good(now);  // an open chip is live: lines may stay silent
  events_.clear();
  if (source_->wait(timeout_ms, events_) < 0) {
    faults_.down(clock_(), source_->describe() + ": " + source_->error());
    source_->close();
    open_ = false;
    return;
  }
  // A silent line is a standing belt or an unpressed button, not a fault: an open chip counts as live.
  faults_.good(clock_());
  for (const auto& e : events_) on_event(e);
}

DeviceState GpioReader::state() const {
  return faults_.state(clock_()) == DeviceState::Down ? DeviceState::Down : DeviceState::Live;
}

GpioTreadmill::GpioTreadmill(const GpioEncoderConfig& config, std::unique_ptr<GpioSource> source,
                             GpioReader::TimeFn clock)
    : config_(config),
      reader_(fmt::format("treadmill (gpio {} line {})", config.chip, config.line), std::move(source),
              config.faults, clock),
      clock_(clock),
      encoder_(config.metres_per_pulse, config.debounce, config.stop_after) {}

void GpioTreadmill::on_event(const LineEvent& e) {
  if (e.line != config_.line) return;
  std::lock_guard lock(mutex_);
  encoder_.edge(e.time, e.rising);
}

std::optional<TreadmillReading> GpioTreadmill::poll(double) {
  if (reader_.state() != DeviceState::Live) return std::nullopt;  // down: the daemon stands the walker still
  const double now = clock_();
  std::lock_guard lock(mutex_);
  TreadmillReading r;
  r.speed = encoder_.speed(now);
  r.time = r.speed > 0.0 ? encoder_.last_pulse() : now;
  return r;
}

std::uint64_t GpioTreadmill::pulses() const {
  std::lock_guard lock(mutex_);
  return encoder_.pulses();
}

std::uint64_t GpioTreadmill::bounces() const {
  std::lock_guard lock(mutex_);
  return encoder_.bounces();
}

GpioButtons::GpioButtons(const GpioButtonsConfig& config, std::unique_ptr<GpioSource> source,
                         GpioReader::TimeFn clock)
    : config_(config),
      reader_(fmt::format("buttons (gpio {})", config.chip), std::move(source), config.faults,
              std::move(clock)),
      filters_(config.lines.size(), EdgeFilter(config.debounce)) {}

void GpioButtons::on_event(const LineEvent& e) {
  // Lines are requested active-low where configured, so `rising` always means "pressed".
  for (std::size_t i = 0; i < config_.lines.size(); ++i) {
    if (config_.lines[i].second != e.line) continue;
    if (filters_[i].accept(e.time, e.rising) && e.rising) {
      std::lock_guard lock(mutex_);
      pending_.push_back({e.time, config_.lines[i].first});
    }
  }
}

std::vector<ButtonPress> GpioButtons::poll(double) {
  std::lock_guard lock(mutex_);
  std::vector<ButtonPress> out;
  out.swap(pending_);
  return out;
}

}  // namespace walk::devices
