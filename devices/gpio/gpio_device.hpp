#pragma once
// GPIO devices through libgpiod (v1 API): a belt encoder on one line (edges to speed) and kiosk buttons on
// others. A reader thread waits for line events with a timeout; events carry the kernel's timestamp. The
// GpioSource seam lets tests feed line events where there are no GPIO chips.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "devices/devices.hpp"
#include "devices/fault.hpp"
#include "devices/gpio/edge_filter.hpp"
#include "devices/reader_thread.hpp"

namespace walk::devices {

struct LineEvent {
  unsigned line = 0;  // offset on the chip
  bool rising = false;
  double time = 0.0;  // seconds, CLOCK_MONOTONIC
};

class GpioSource {
 public:
  virtual ~GpioSource() = default;
  [[nodiscard]] virtual std::string open() = 0;  // requests the lines for both edges; empty on success
  // Appends the events that arrive within timeout_ms; returns how many, or < 0 when the chip failed.
  virtual int wait(int timeout_ms, std::vector<LineEvent>& out) = 0;
  virtual void close() = 0;
  [[nodiscard]] virtual std::string error() const = 0;
  [[nodiscard]] virtual std::string describe() const = 0;
};

// chip: "gpiochip0", "/dev/gpiochip0", a label or a number (gpiod_chip_open_lookup).
[[nodiscard]] std::unique_ptr<GpioSource> make_gpiod_source(const std::string& chip,
                                                            std::vector<unsigned> lines, bool active_low,
                                                            const std::string& consumer);

struct GpioEncoderConfig {
  std::string chip;
  unsigned line = 0;
  bool active_low = false;
  double metres_per_pulse = 0.01;
  double debounce = 0.0005;  // seconds; shorter than half the fastest pulse period
  double stop_after = 0.5;   // no pulse this long: the belt stands
  FaultPolicy faults;
};

struct GpioButtonsConfig {
  std::string chip;
  std::vector<std::pair<Button, unsigned>> lines;  // which line each button is wired to
  bool active_low = true;                          // buttons usually pull the line to ground
  double debounce = 0.02;
  FaultPolicy faults;
};

// Shared by both GPIO devices: opens the source with backoff and hands events to a callback.
class GpioReader {
 public:
  using TimeFn = std::function<double()>;
  GpioReader(std::string name, std::unique_ptr<GpioSource> source, FaultPolicy policy, TimeFn clock);
  ~GpioReader() { thread_.stop(); }
  void start(std::function<void(const LineEvent&)> on_event, int timeout_ms = 50);
  void step(const std::function<void(const LineEvent&)>& on_event, int timeout_ms);
  [[nodiscard]] DeviceState state() const;
  [[nodiscard]] const FaultTracker& faults() const { return faults_; }

 private:
  std::unique_ptr<GpioSource> source_;
  FaultTracker faults_;
  TimeFn clock_;
  bool open_ = false;
  std::vector<LineEvent> events_;
  ReaderThread thread_;
};

class GpioTreadmill final : public Treadmill {
 public:
  GpioTreadmill(const GpioEncoderConfig& config, std::unique_ptr<GpioSource> source,
                GpioReader::TimeFn clock = monotonic_seconds);
  void start() {
    reader_.start([this](const LineEvent& e) { on_event(e); });
  }
  void step(int timeout_ms) {
    reader_.step([this](const LineEvent& e) { on_event(e); }, timeout_ms);
  }
  std::optional<TreadmillReading> poll(double now) override;
  [[nodiscard]] DeviceState state() const override { return reader_.state(); }
  [[nodiscard]] std::string name() const override { return reader_.faults().device(); }
  [[nodiscard]] std::uint64_t pulses() const;
  [[nodiscard]] std::uint64_t bounces() const;

 private:
  void on_event(const LineEvent& e);
  GpioEncoderConfig config_;
  GpioReader reader_;
  GpioReader::TimeFn clock_;
  mutable std::mutex mutex_;
  BeltEncoder encoder_;
};

class GpioButtons final : public ButtonPanel {
 public:
  GpioButtons(const GpioButtonsConfig& config, std::unique_ptr<GpioSource> source,
              GpioReader::TimeFn clock = monotonic_seconds);
  void start() {
    reader_.start([this](const LineEvent& e) { on_event(e); });
  }
  void step(int timeout_ms) {
    reader_.step([this](const LineEvent& e) { on_event(e); }, timeout_ms);
  }
  std::vector<ButtonPress> poll(double now) override;
  [[nodiscard]] DeviceState state() const override { return reader_.state(); }
  [[nodiscard]] std::string name() const override { return reader_.faults().device(); }

 private:
  void on_event(const LineEvent& e);
  GpioButtonsConfig config_;
  GpioReader reader_;
  std::vector<EdgeFilter> filters_;  // per configured line
  std::mutex mutex_;
  std::vector<ButtonPress> pending_;
};

}  // namespace walk::devices
