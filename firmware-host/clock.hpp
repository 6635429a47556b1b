#pragma once
// Injectable time source: the daemon reads time only through a Clock, so a simulated run (trace devices plus
// SimulatedClock) is deterministic and runs as fast as the renderer allows.
#include <chrono>

namespace walk::kiosk {

class Clock {
 public:
  virtual ~Clock() = default;
  [[nodiscard]] virtual double now() const = 0;  // seconds since the clock started
};

// Advanced explicitly by the main loop, one fixed frame step at a time.
class SimulatedClock final : public Clock {
 public:
  explicit SimulatedClock(double start = 0.0) : now_(start) {}
  [[nodiscard]] double now() const override { return now_; }
  void advance(double seconds) { now_ += seconds; }
  void set(double seconds) { now_ = seconds; }  // frame * step avoids summing rounding errors

 private:
  double now_;
};

// Wall-clock time for real kiosks, monotonic so NTP steps never make the walker jump.
class SteadyClock final : public Clock {
 public:
  SteadyClock() : start_(std::chrono::steady_clock::now()) {}
  [[nodiscard]] double now() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace walk::kiosk
