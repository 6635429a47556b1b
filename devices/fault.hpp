#pragma once
// One device's health: a fault (gone, timed out, garbage) is logged once per episode and then at most every
// `log_every` seconds as a count; reopening is retried with exponential backoff; recovery is logged once.
// Thread-safe: a backend's reader thread records, the daemon's loop reads the state.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "devices/devices.hpp"

namespace walk::devices {

struct FaultPolicy {
  double stale_after = 0.5;  // seconds without a good reading before an open device counts as stale
  double retry_min = 0.25;   // first reopen delay, doubled per failure ...
  double retry_max = 8.0;    // ... up to this
  double log_every = 60.0;   // while a fault lasts, one summary line per this many seconds
};

class FaultTracker {
 public:
  FaultTracker(std::string device, FaultPolicy policy) : device_(std::move(device)), policy_(policy) {}

  void opened();                                      // open again: stale until the first good reading
  void good(double now);                              // a valid reading arrived
  void garbage(double now, const std::string& what);  // a reading arrived but is invalid: stays open
  void timeout(double now, const std::string& what);  // open, silent too long
  void down(double now, const std::string& what);     // could not open, or the device went away
  [[nodiscard]] bool may_reopen(double now) const;    // backoff elapsed since the last down()
  [[nodiscard]] DeviceState state(double now) const;
  [[nodiscard]] std::uint64_t faults() const;  // all fault events, logged or not
  [[nodiscard]] std::uint64_t logged() const;  // fault lines written (rate-limited)
  [[nodiscard]] double retry_delay() const;    // the current backoff
  [[nodiscard]] const FaultPolicy& policy() const { return policy_; }
  [[nodiscard]] const std::string& device() const { return device_; }

 private:
  void record(double now, const std::string& kind, const std::string& what);  // with mutex_ held

  std::string device_;
  FaultPolicy policy_;
  mutable std::mutex mutex_;
  bool open_ = false;      // last event was not down()
  bool in_fault_ = false;  // an episode is running: the next good() logs the recovery
  double last_good_ = -1e300;
  double next_reopen_ = -1e300;
  double delay_ = 0.0;
  double next_log_ = -1e300;
  std::uint64_t faults_ = 0, logged_ = 0, unlogged_ = 0;
};

// The reopen step every reader shares: when `source` is closed and the backoff has run out, open it (a
// failure is recorded as down()). Returns whether it is open now. While backing off on a running thread it
// sleeps `slice_ms` rather than spin; tests call their reader's step() with no thread, which never sleeps.
template <typename Source>
bool ensure_open(Source& source, bool& open, FaultTracker& faults, double now, bool threaded, int slice_ms) {
  if (open) return true;
  if (!faults.may_reopen(now)) {
    if (threaded) std::this_thread::sleep_for(std::chrono::milliseconds(slice_ms));
    return false;
  }
  if (auto why = source.open(); !why.empty()) {
    faults.down(now, why);
    return false;
  }
  open = true;
  return true;
}

}  // namespace walk::devices
