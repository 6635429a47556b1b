#pragma once
// Edge debouncing and belt-encoder arithmetic, kept free of libgpiod so tests feed line events directly.
#include <cstdint>
#include <deque>

namespace walk::devices {

// Accepts an edge only when it changes the level and comes at least `debounce` seconds after the last
// accepted edge: contact bounce (a burst of edges within microseconds) collapses into the first edge.
class EdgeFilter {
 public:
  explicit EdgeFilter(double debounce, bool initial_level = false)
      : debounce_(debounce), level_(initial_level) {}
  bool accept(double time, bool rising);  // true when the edge counts
  [[nodiscard]] bool level() const { return level_; }
  [[nodiscard]] std::uint64_t rejected() const { return rejected_; }

 private:
  double debounce_;
  bool level_;
  double last_ = -1e300;
  std::uint64_t rejected_ = 0;
};

// Belt speed from an encoder's debounced rising edges: distance per pulse / mean period of the last few
// pulses. No pulse for `stop_after` seconds (or longer than twice the last period) means the belt stopped.
class BeltEncoder {
 public:
  BeltEncoder(double metres_per_pulse, double debounce, double stop_after, std::size_t average_pulses = 4)
      : metres_per_pulse_(metres_per_pulse),
        stop_after_(stop_after),
        average_(average_pulses),
        filter_(debounce) {}
  void edge(double time, bool rising);
  [[nodiscard]] double speed(double now) const;
  [[nodiscard]] double last_pulse() const { return pulses_.empty() ? -1e300 : pulses_.back(); }
  [[nodiscard]] std::uint64_t pulses() const { return count_; }
  [[nodiscard]] std::uint64_t bounces() const { return filter_.rejected(); }

 private:
  double metres_per_pulse_, stop_after_;
  std::size_t average_;
  EdgeFilter filter_;
  std::deque<double> pulses_;  // times of the last average_ + 1 rising edges
  std::uint64_t count_ = 0;
};

}  // namespace walk::devices
