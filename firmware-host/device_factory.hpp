#pragma once
// Opens the devices a kiosk config names. Only the mock (trace replay) backend exists so far; hid, gpio and
// modbus backends plug in here.
#include <memory>

#include "devices/devices.hpp"
#include "firmware-host/kiosk_config.hpp"

namespace walk::kiosk {

struct DeviceSet {
  std::unique_ptr<devices::Treadmill> treadmill;       // null: the walker stands still
  std::unique_ptr<devices::HeadTracker> head_tracker;  // null: looks along the body heading
  std::unique_ptr<devices::DimmerPanel> dimmer_panel;  // null: circuits keep their default levels
};

// Throws walk::Error naming the trace file when a device cannot be opened.
[[nodiscard]] DeviceSet open_devices(const DevicesConfig& config);

}  // namespace walk::kiosk
