#include "firmware-host/device_factory.hpp"

#include "devices/gpio/gpio_device.hpp"
#include "devices/hid/hid_device.hpp"
#include "devices/mock/trace_devices.hpp"

namespace walk::kiosk {
namespace {

std::unique_ptr<devices::HidReader> hid_reader(const std::string& role, const DeviceConfig& d) {
  auto source = devices::make_hidapi_source(d.hid);
  auto reader = std::make_unique<devices::HidReader>(role + " (" + source->describe() + ")",
                                                     std::move(source), d.hid.layout, d.hid.faults);
  reader->start(d.hid.read_timeout_ms);
  return reader;
}

}  // namespace

DeviceSet open_devices(const DevicesConfig& config) {
  DeviceSet set;
  if (const auto& d = config.treadmill) {
    if (d->backend == "mock") {
      set.treadmill = std::make_unique<devices::TraceTreadmill>(d->trace);
    } else if (d->backend == "hid") {
      set.treadmill = std::make_unique<devices::HidTreadmill>(hid_reader("treadmill", *d));
    } else {
      auto t = std::make_unique<devices::GpioTreadmill>(
          d->encoder,
          devices::make_gpiod_source(d->encoder.chip, {d->encoder.line}, d->encoder.active_low, "walkd"));
      t->start();
      set.treadmill = std::move(t);
    }
  }
  if (const auto& d = config.head_tracker) {
    if (d->backend == "mock")
      set.head_tracker = std::make_unique<devices::TraceHeadTracker>(d->trace);
    else
      set.head_tracker = std::make_unique<devices::HidHeadTracker>(hid_reader("head tracker", *d));
  }
  if (const auto& d = config.dimmer_panel) {
    if (d->backend == "mock") {
      set.dimmer_panel = std::make_unique<devices::TraceDimmerPanel>(d->trace);
    } else {
      auto p = std::make_unique<devices::ModbusDimmerPanel>(d->modbus);
      p->start();
      set.modbus = p.get();
      set.dimmer_panel = std::move(p);
    }
  }
  if (const auto& d = config.buttons) {
    if (d->backend == "mock") {
      set.buttons = std::make_unique<devices::TraceButtons>(d->trace);
    } else {
      std::vector<unsigned> lines;
      for (const auto& [button, line] : d->buttons.lines) lines.push_back(line);
      auto b = std::make_unique<devices::GpioButtons>(
          d->buttons, devices::make_gpiod_source(d->buttons.chip, lines, d->buttons.active_low, "walkd"));
      b->start();
      set.buttons = std::move(b);
    }
  }
  return set;
}

}  // namespace walk::kiosk
