#pragma once
// The systemd drop-in that opens walkd's sandbox exactly as far as the kiosk config needs: DeviceAllow for
// each configured device node, and the network only when a Modbus TCP panel is configured (then only to
// that host). walkd.service itself allows no devices but the GPU and no network.
//   walkd --config /etc/walkthrough/kiosk.toml --print-unit-dropin >
//   /etc/systemd/system/walkd.service.d/devices.conf
#include <string>

#include "firmware-host/kiosk_config.hpp"

namespace walk::kiosk {

[[nodiscard]] std::string unit_dropin(const KioskConfig& config);

}  // namespace walk::kiosk
