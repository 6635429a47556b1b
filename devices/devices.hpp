#pragma once
// Device interfaces. Every reading carries the time it was taken (seconds on the daemon's clock), so the
// daemon can measure latency and tell stale devices from live ones. devices/ knows nothing of rendering.
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace walk::devices {

struct TreadmillReading {
  double time = 0.0;
  double speed = 0.0;     // belt speed, metres per second, >= 0
  double steering = 0.0;  // radians, positive turns left; 0 when the treadmill has no steering
};

struct HeadReading {
  double time = 0.0;
  double yaw = 0.0;    // radians about +z, 0 looks along +x, positive turns left
  double pitch = 0.0;  // radians, positive looks up
};

struct DimmerReading {
  double time = 0.0;
  std::vector<double> levels;  // one per channel, 0..1
};

class Treadmill {
 public:
  virtual ~Treadmill() = default;
  // The newest reading taken at or before `now`, or nothing if there is none yet or the device is stale.
  virtual std::optional<TreadmillReading> poll(double now) = 0;
};

class HeadTracker {
 public:
  virtual ~HeadTracker() = default;
  virtual std::optional<HeadReading> poll(double now) = 0;
};

class DimmerPanel {
 public:
  virtual ~DimmerPanel() = default;
  [[nodiscard]] virtual std::size_t channel_count() const = 0;
  virtual std::optional<DimmerReading> poll(double now) = 0;
};

}  // namespace walk::devices
