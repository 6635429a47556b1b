// walk-panel-sim: a Modbus dimmer-panel simulator for trying walkd without hardware.
//   walk-panel-sim --tcp 127.0.0.1:1502 --registers 4 [--set 0=1000 ...]
//   walk-panel-sim --rtu /dev/pts/5 --baud 19200 --registers 4
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "devices/sim/panel_simulator.hpp"
#include "model/error.hpp"
#include "model/version.hpp"

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) {
  g_stop = true;
}
}  // namespace

int main(int argc, char** argv) {
  std::string tcp, rtu;
  int registers = 8, baud = 19200, slave = 1;
  std::vector<std::pair<int, int>> sets;
  if (argc == 2 && std::string(argv[1]) == "--version") {
    std::printf("walk-panel-sim %s\n", walk::version());
    return 0;
  }
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--tcp")
      tcp = v;
    else if (k == "--rtu")
      rtu = v;
    else if (k == "--registers")
      registers = std::atoi(v.c_str());
    else if (k == "--baud")
      baud = std::atoi(v.c_str());
    else if (k == "--slave")
      slave = std::atoi(v.c_str());
    else if (k == "--set" && v.find('=') != std::string::npos)
      sets.emplace_back(std::atoi(v.substr(0, v.find('=')).c_str()),
                        std::atoi(v.substr(v.find('=') + 1).c_str()));
    else {
      std::fprintf(stderr, "walk-panel-sim: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  if (tcp.empty() == rtu.empty()) {
    std::fprintf(stderr,
                 "usage: walk-panel-sim (--tcp HOST:PORT | --rtu DEVICE [--baud N]) [--registers N] "
                 "[--slave N] [--set REG=VALUE]...\n");
    return 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    std::unique_ptr<walk::devices::PanelSimulator> sim;
    if (!tcp.empty()) {
      const auto colon = tcp.rfind(':');
      sim = walk::devices::PanelSimulator::tcp(tcp.substr(0, colon), std::atoi(tcp.substr(colon + 1).c_str()),
                                               registers, slave);
      std::printf("walk-panel-sim: modbus tcp on port %d, %d registers\n", sim->port(), registers);
    } else {
      sim = walk::devices::PanelSimulator::rtu(rtu, baud, 'E', registers, slave);
      std::printf("walk-panel-sim: modbus rtu on %s, %d registers\n", rtu.c_str(), registers);
    }
    std::fflush(stdout);
    for (auto [r, v] : sets) sim->set_register(r, static_cast<std::uint16_t>(v));
    while (!g_stop) pause();
  } catch (const walk::Error& e) {
    std::fprintf(stderr, "walk-panel-sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
