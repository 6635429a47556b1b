#pragma once
// Opens the devices a kiosk config names and starts their reader threads. Hardware that is missing or
// fails does not make this throw: the device starts Down and its thread retries with backoff. Only config
// mistakes (an unreadable trace, a bad report layout) throw.
#include <memory>

#include "devices/devices.hpp"
#include "devices/modbus/modbus_panel.hpp"
#include "firmware-host/kiosk_config.hpp"

namespace walk::kiosk {

struct DeviceSet {
  std::unique_ptr<devices::Treadmill> treadmill;       // null: the walker stands still
  std::unique_ptr<devices::HeadTracker> head_tracker;  // null: looks along the body heading
  std::unique_ptr<devices::DimmerPanel> dimmer_panel;  // null: circuits keep their default levels
  std::unique_ptr<devices::ButtonPanel> buttons;       // null: no buttons
  devices::ModbusDimmerPanel* modbus = nullptr;        // the panel again when it is Modbus: poll statistics
};

// Throws walk::Error naming the trace file or config key when a device is misconfigured.
[[nodiscard]] DeviceSet open_devices(const DevicesConfig& config);

}  // namespace walk::kiosk
