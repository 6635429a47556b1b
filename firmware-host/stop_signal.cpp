#include "firmware-host/stop_signal.hpp"

#include <csignal>

namespace walk::kiosk {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<bool> g_reload{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler may only touch lock-free atomics");

extern "C" void on_stop_signal(int) {
  g_stop.store(true);
}

extern "C" void on_reload_signal(int) {
  g_reload.store(true);
}

}  // namespace

std::atomic<bool>& reload_flag() {
  return g_reload;
}

std::atomic<bool>& stop_flag() {
  return g_stop;
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  action.sa_handler = on_reload_signal;
  sigaction(SIGHUP, &action, nullptr);
}

}  // namespace walk::kiosk
