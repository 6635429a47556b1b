#pragma once
// SIGTERM (systemd stop) and SIGINT (Ctrl-C) ask the loop to finish its frame, write its summary and exit;
// SIGHUP (systemctl reload) asks it to re-read the kiosk config between frames.
#include <atomic>

namespace walk::kiosk {

// The process's global state: set from the signal handlers, read by the main loop.
[[nodiscard]] std::atomic<bool>& stop_flag();
[[nodiscard]] std::atomic<bool>& reload_flag();
void install_stop_handlers();

}  // namespace walk::kiosk
