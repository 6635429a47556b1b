#include "devices/devices.hpp"

#include <time.h>

namespace walk::devices {

const char* button_name(Button b) {
  switch (b) {
    case Button::ReturnToStart:
      return "return_to_start";
    case Button::NextBuilding:
      return "next_building";
  }
  return "?";
}

std::optional<Button> parse_button(const std::string& name) {
  if (name == "return_to_start") return Button::ReturnToStart;
  if (name == "next_building") return Button::NextBuilding;
  return std::nullopt;
}

const char* state_name(DeviceState s) {
  switch (s) {
    case DeviceState::Live:
      return "live";
    case DeviceState::Stale:
      return "stale";
    case DeviceState::Down:
      return "down";
  }
  return "?";
}

double monotonic_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace walk::devices
