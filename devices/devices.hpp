#pragma once
// Device interfaces. Every reading carries the time it was taken: trace (mock) devices use the daemon's
// clock, hardware backends use CLOCK_MONOTONIC seconds (devices::monotonic_seconds), which is also the
// daemon's real-time clock, so latency from a reading to the frame showing it can be measured.
// devices/ knows nothing of rendering.
#include <cstdint>
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
  bool has_position = false;
  double x = 0.0, y = 0.0, z = 0.0;  // metres, tracker frame: offset of the head from its rest position
};

struct DimmerReading {
  double time = 0.0;
  std::vector<double> levels;  // one per channel, 0..1
};

// Kiosk buttons: the client has no keyboard, only these.
enum class Button : std::uint8_t { ReturnToStart, NextBuilding };
inline constexpr std::size_t kButtonCount = 2;
[[nodiscard]] const char* button_name(Button b);
[[nodiscard]] std::optional<Button> parse_button(const std::string& name);

struct ButtonPress {
  double time = 0.0;
  Button button = Button::ReturnToStart;
};

// Health as STATUS lines and logs show it.
enum class DeviceState : std::uint8_t {
  Live,   // readings arrive
  Stale,  // opened, but no good reading within its timeout: last good values / safe defaults apply
  Down,   // cannot be opened or has gone; retried with backoff
};
[[nodiscard]] const char* state_name(DeviceState s);

class Device {
 public:
  virtual ~Device() = default;
  [[nodiscard]] virtual DeviceState state() const { return DeviceState::Live; }
  [[nodiscard]] virtual std::string name() const = 0;  // for logs: "treadmill (hid /dev/hidraw0)"
  // True when readings are stamped with monotonic_seconds() (hardware), false for the daemon's clock
  // (traces).
  [[nodiscard]] virtual bool monotonic_timestamps() const { return true; }
};

class Treadmill : public Device {
 public:
  // The newest reading taken at or before `now`, or nothing if there is none yet or the device is stale.
  virtual std::optional<TreadmillReading> poll(double now) = 0;
};

class HeadTracker : public Device {
 public:
  virtual std::optional<HeadReading> poll(double now) = 0;
};

class DimmerPanel : public Device {
 public:
  [[nodiscard]] virtual std::size_t channel_count() const = 0;
  virtual std::optional<DimmerReading> poll(double now) = 0;
};

class ButtonPanel : public Device {
 public:
  // Presses since the last call, oldest first (a press is reported once, on its debounced edge).
  virtual std::vector<ButtonPress> poll(double now) = 0;
};

// CLOCK_MONOTONIC in seconds: the timestamp of hardware readings.
[[nodiscard]] double monotonic_seconds();

}  // namespace walk::devices
