#pragma once
// Reads one [devices.NAME] table: the backend and its settings (HID report layout, GPIO lines, Modbus
// register map, poll rate, timeouts, retries, fault policy). Times are seconds unless the key says _ms.
#include <string>

#include "firmware-host/kiosk_config.hpp"
#include "model/toml_table.hpp"

namespace walk::kiosk {

enum class DeviceRole { Treadmill, HeadTracker, DimmerPanel, Buttons };

[[nodiscard]] DeviceConfig read_device(const TomlTable& s, DeviceRole role, const std::string& config_dir);

}  // namespace walk::kiosk
