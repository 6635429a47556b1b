#pragma once
// systemd notifications: READY once the first frame is up, WATCHDOG every frame when the unit asks for it,
// STATUS about once a second. Outside systemd (no NOTIFY_SOCKET) every call is a cheap no-op.
#include <cstdint>
#include <string>

namespace walk::kiosk {

class SystemdNotifier {
 public:
  SystemdNotifier();
  void ready();
  void frame(double wall_now, const std::string& status);  // watchdog ping, throttled status
  void stopping();
  [[nodiscard]] bool watchdog_enabled() const { return watchdog_usec_ > 0; }

 private:
  bool ready_sent_ = false;
  std::uint64_t watchdog_usec_ = 0;
  double next_status_ = 0.0;
};

}  // namespace walk::kiosk
