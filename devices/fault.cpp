#include "devices/fault.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace walk::devices {

void FaultTracker::opened() {
  std::lock_guard lock(mutex_);
  open_ = true;
}

void FaultTracker::good(double now) {
  std::lock_guard lock(mutex_);
  open_ = true;
  last_good_ = now;
  delay_ = 0.0;
  if (in_fault_) {
    spdlog::info("{}: recovered ({} fault events in this episode)", device_, unlogged_ + 1);
    in_fault_ = false;
    unlogged_ = 0;
    next_log_ = -1e300;  // a new episode logs at once
  }
}

void FaultTracker::record(double now, const std::string& kind, const std::string& what) {
  ++faults_;
  if (!in_fault_ || now >= next_log_) {
    if (unlogged_ > 0)
      spdlog::warn("{}: {}: {} ({} more fault events since the last message)", device_, kind, what,
                   unlogged_);
    else
      spdlog::warn("{}: {}: {}", device_, kind, what);
    ++logged_;
    unlogged_ = 0;
    next_log_ = now + policy_.log_every;
  } else {
    ++unlogged_;
  }
  in_fault_ = true;
}

void FaultTracker::garbage(double now, const std::string& what) {
  std::lock_guard lock(mutex_);
  open_ = true;
  record(now, "bad data, ignored", what);
}

void FaultTracker::timeout(double now, const std::string& what) {
  std::lock_guard lock(mutex_);
  open_ = true;
  record(now, "stale, using safe values", what);
}

void FaultTracker::down(double now, const std::string& what) {
  std::lock_guard lock(mutex_);
  open_ = false;
  delay_ = delay_ <= 0.0 ? policy_.retry_min : std::min(delay_ * 2.0, policy_.retry_max);
  next_reopen_ = now + delay_;
  record(now, "unavailable, retrying with backoff", fmt::format("{} (next try in {:g} s)", what, delay_));
}

bool FaultTracker::may_reopen(double now) const {
  std::lock_guard lock(mutex_);
  return now >= next_reopen_;
}

DeviceState FaultTracker::state(double now) const {
  std::lock_guard lock(mutex_);
  if (!open_) return DeviceState::Down;
  return now - last_good_ <= policy_.stale_after ? DeviceState::Live : DeviceState::Stale;
}

std::uint64_t FaultTracker::faults() const {
  std::lock_guard lock(mutex_);
  return faults_;
}

std::uint64_t FaultTracker::logged() const {
  std::lock_guard lock(mutex_);
  return logged_;
}

double FaultTracker::retry_delay() const {
  std::lock_guard lock(mutex_);
  return delay_;
}

}  // namespace walk::devices
