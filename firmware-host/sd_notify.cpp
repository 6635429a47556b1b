#include "firmware-host/sd_notify.hpp"

#include <systemd/sd-daemon.h>

namespace walk::kiosk {

SystemdNotifier::SystemdNotifier() {
  std::uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) > 0) watchdog_usec_ = usec;
}

void SystemdNotifier::ready() {
  if (ready_sent_) return;
  sd_notify(0, "READY=1");
  ready_sent_ = true;
}

void SystemdNotifier::frame(double wall_now, const std::string& status) {
  if (watchdog_usec_ > 0) sd_notify(0, "WATCHDOG=1");
  if (wall_now >= next_status_) {
    sd_notify(0, ("STATUS=" + status).c_str());
    next_status_ = wall_now + 1.0;
  }
}

void SystemdNotifier::stopping() {
  sd_notify(0, "STOPPING=1");
}

}  // namespace walk::kiosk
