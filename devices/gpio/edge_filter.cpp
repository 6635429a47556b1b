#include "devices/gpio/edge_filter.hpp"

#include <algorithm>

namespace walk::devices {

bool EdgeFilter::accept(double time, bool rising) {
  if (rising == level_ || time - last_ < debounce_) {
    ++rejected_;
    return false;
  }
  level_ = rising;
  last_ = time;
  return true;
}

void BeltEncoder::edge(double time, bool rising) {
  if (!filter_.accept(time, rising) || !rising) return;
  pulses_.push_back(time);
  ++count_;
  while (pulses_.size() > average_ + 1) pulses_.pop_front();
}

double BeltEncoder::speed(double now) const {
  if (pulses_.size() < 2) return 0.0;
  const double span = pulses_.back() - pulses_.front();
  const double period = span / static_cast<double>(pulses_.size() - 1);
  const double last_period = pulses_.back() - pulses_[pulses_.size() - 2];
  if (period <= 0.0) return 0.0;
  const double silent = now - pulses_.back();
  if (silent > stop_after_ || silent > 2.0 * std::max(last_period, period)) return 0.0;
  return metres_per_pulse_ / period;
}

}  // namespace walk::devices
