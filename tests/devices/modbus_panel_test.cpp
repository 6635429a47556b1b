// The Modbus dimmer panel against the simulator: real libmodbus on both sides, TCP on 127.0.0.1 and RTU over
// a socat pty pair. step() is called directly (no poller thread), so nothing here depends on timing except
// libmodbus's own response timeout.
#include "devices/modbus/modbus_panel.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "devices/sim/panel_simulator.hpp"

extern char** environ;

namespace walk::devices {
namespace modbus_panel_test {  // named, not anonymous: the suite compiles as unity batches

ModbusPanelConfig tcp_config(int port) {
  ModbusPanelConfig c;
  c.port = port;
  c.registers = {0, 1, 2, 3};
  c.timeout = 2.0;  // generous: a loaded CI machine must not turn a slow answer into a fault
  c.retries = 1;
  c.faults.retry_min = 0.0;  // tests step explicitly: reconnect on the next step
  c.faults.retry_max = 0.0;
  return c;
}

TEST(ModbusPanel, ReadsRegistersAsLevelsOverTcp) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 8);
  sim->set_register(0, 1000);
  sim->set_register(2, 250);
  ModbusDimmerPanel panel(tcp_config(sim->port()));
  ASSERT_TRUE(panel.step());
  const auto r = panel.poll(0);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->levels, (std::vector<double>{1.0, 0.0, 0.25, 0.0}));
  EXPECT_EQ(panel.state(), DeviceState::Live);
  sim->set_register(1, 500);
  ASSERT_TRUE(panel.step());
  EXPECT_DOUBLE_EQ(panel.poll(0)->levels[1], 0.5);
  EXPECT_EQ(panel.round_trips().size(), 2u);
}

TEST(ModbusPanel, ScatteredRegistersAndInputRegisters) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 300);
  sim->set_register(7, 100);
  sim->set_register(290, 900);
  auto c = tcp_config(sim->port());
  c.registers = {290, 7};  // 284 apart: more than one request may carry
  c.input_registers = true;
  ModbusDimmerPanel panel(c);
  ASSERT_TRUE(panel.step());
  EXPECT_EQ(panel.poll(0)->levels, (std::vector<double>{0.9, 0.1}));
}

TEST(ModbusPanel, OutOfRangeValueIsGarbageAndLastGoodLevelsStay) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 4);
  sim->set_register(0, 400);
  ModbusDimmerPanel panel(tcp_config(sim->port()));
  ASSERT_TRUE(panel.step());
  sim->set_register(0, 60000);
  EXPECT_FALSE(panel.step());
  EXPECT_DOUBLE_EQ(panel.poll(0)->levels[0], 0.4);
  EXPECT_EQ(panel.faults().faults(), 1u);
}

TEST(ModbusPanel, SimulatorStoppedAndRestartedReconnectsAndLevelsResume) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 4);
  const int port = sim->port();
  sim->set_register(3, 300);
  ModbusDimmerPanel panel(tcp_config(port));
  ASSERT_TRUE(panel.step());
  sim.reset();  // every connection closes at once, like a killed process
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(panel.step());
  EXPECT_EQ(panel.state(), DeviceState::Down);
  EXPECT_DOUBLE_EQ(panel.poll(0)->levels[3], 0.3);  // last good levels stay in use
  EXPECT_EQ(panel.faults().logged(), 1u);           // logged once for the episode

  sim = PanelSimulator::tcp("127.0.0.1", port, 4);
  sim->set_register(3, 700);
  bool back = false;
  for (int i = 0; i < 5 && !back; ++i) back = panel.step();
  ASSERT_TRUE(back);
  EXPECT_EQ(panel.state(), DeviceState::Live);
  EXPECT_DOUBLE_EQ(panel.poll(0)->levels[3], 0.7);
}

TEST(ModbusPanel, SilentPanelTimesOutRetriesAndReconnects) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 4);
  auto c = tcp_config(sim->port());
  c.timeout = 0.3;
  c.retries = 2;
  ModbusDimmerPanel panel(c);
  ASSERT_TRUE(panel.step());
  const auto before = sim->requests();
  sim->set_silent(true);
  EXPECT_FALSE(panel.step());
  for (int i = 0; i < 400 && sim->requests() - before < 3; ++i)  // the server may lag the client's timeout
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(sim->requests() - before, 3u);  // first try + 2 retries
  EXPECT_EQ(panel.state(), DeviceState::Down);
  sim->set_silent(false);
  EXPECT_TRUE(panel.step());
}

TEST(ModbusPanel, NothingListeningIsDownWithTheAddressInTheLog) {
  auto sim = PanelSimulator::tcp("127.0.0.1", 0, 4);
  const int port = sim->port();
  sim.reset();
  ModbusDimmerPanel panel(tcp_config(port));
  EXPECT_FALSE(panel.step());
  EXPECT_EQ(panel.state(), DeviceState::Down);
  EXPECT_FALSE(panel.poll(0));
  EXPECT_NE(panel.name().find("127.0.0.1:" + std::to_string(port)), std::string::npos);
}

// RTU: socat joins two ptys; the simulator serves one end, the panel polls the other.
TEST(ModbusPanel, RtuOverASocatPtyPair) {
  if (access("/usr/bin/socat", X_OK) != 0) GTEST_SKIP() << "socat is not installed (scripts/install-deps.sh)";
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("walk_rtu_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string a = (dir / "panel").string(), b = (dir / "walkd").string();
  const std::string la = "pty,raw,echo=0,link=" + a, lb = "pty,raw,echo=0,link=" + b;
  const char* argv[] = {"socat", la.c_str(), lb.c_str(), nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawnp(&pid, "socat", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  for (int i = 0; i < 500 && !(fs::exists(a) && fs::exists(b)); ++i)  // bounded: 5 s at most
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(a) && fs::exists(b)) << "socat did not create the pty pair";
  {
    auto sim = PanelSimulator::rtu(a, 38400, 'E', 4);
    sim->set_register(1, 1000);
    ModbusPanelConfig c;
    c.transport = ModbusPanelConfig::Transport::Rtu;
    c.device = b;
    c.baud = 38400;
    c.registers = {0, 1};
    c.timeout = 0.5;
    ModbusDimmerPanel panel(c);
    bool ok = false;
    for (int i = 0; i < 3 && !ok; ++i) ok = panel.step();
    ASSERT_TRUE(ok) << "no RTU answer";
    EXPECT_EQ(panel.poll(0)->levels, (std::vector<double>{0.0, 1.0}));
    sim->set_register(0, 500);
    ASSERT_TRUE(panel.step());
    EXPECT_DOUBLE_EQ(panel.poll(0)->levels[0], 0.5);
  }
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  fs::remove_all(dir);
}

}  // namespace modbus_panel_test
}  // namespace walk::devices
