#include "firmware-host/device_factory.hpp"

#include "devices/mock/trace_devices.hpp"

namespace walk::kiosk {

DeviceSet open_devices(const DevicesConfig& config) {
  DeviceSet set;
  // The config reader accepts only backend = "mock", so every configured device is a trace replay.
  if (config.treadmill) set.treadmill = std::make_unique<devices::TraceTreadmill>(config.treadmill->trace);
  if (config.head_tracker)
    set.head_tracker = std::make_unique<devices::TraceHeadTracker>(config.head_tracker->trace);
  if (config.dimmer_panel)
    set.dimmer_panel = std::make_unique<devices::TraceDimmerPanel>(config.dimmer_panel->trace);
  return set;
}

}  // namespace walk::kiosk
