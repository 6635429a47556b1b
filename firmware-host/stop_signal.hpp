#pragma once
// SIGTERM (systemd stop) and SIGINT (Ctrl-C) ask the loop to finish its frame, write its summary and exit.
#include <atomic>

namespace walk::kiosk {

// The process's one piece of global state: set from the signal handler, read by the main loop.
[[nodiscard]] std::atomic<bool>& stop_flag();
void install_stop_handlers();

}  // namespace walk::kiosk
