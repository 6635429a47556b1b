// walkd's loop with real device backends: the Modbus panel simulator (in this process, or a child process
// that is killed and restarted), missing hardware, buttons and a SIGHUP-style reload. Waits are bounded
// loops on a state change, never assertions on time.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "compiler/pipeline.hpp"
#include "devices/sim/panel_simulator.hpp"
#include "fake_renderer.hpp"
#include "firmware-host/daemon.hpp"
#include "gl_probe_renderer.hpp"
#include "model/error.hpp"
#include "test_bundle.hpp"

namespace walk::kiosk {
namespace device_walk_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

// Polls `done` every 5 ms for at most `ms` milliseconds.
template <typename F>
bool wait_for(F done, int ms = 10000) {
  for (int i = 0; i < ms / 5; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

DeviceConfig modbus_device(int port, std::vector<int> registers) {
  DeviceConfig d;
  d.backend = "modbus";
  d.modbus.port = port;
  d.modbus.registers = std::move(registers);
  d.modbus.poll_hz = 100.0;
  d.modbus.timeout = 2.0;  // generous: only the kill may fault the panel, not a loaded machine
  d.modbus.retries = 1;
  d.modbus.faults.retry_min = 0.05;
  d.modbus.faults.retry_max = 0.2;
  d.modbus.faults.stale_after = 0.5;
  return d;
}

// A panel simulator in a child process, so it can be killed for real. Returns its pid; `port` in/out.
pid_t spawn_simulator(int& port, std::uint16_t reg0) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    try {
      auto sim = devices::PanelSimulator::tcp("127.0.0.1", port, 4);
      sim->set_register(0, reg0);
      const int p = sim->port();
      if (write(fds[1], &p, sizeof p) != sizeof p) _exit(1);
      for (;;) pause();
    } catch (...) {
      _exit(1);
    }
  }
  close(fds[1]);
  int p = 0;
  const bool ok = read(fds[0], &p, sizeof p) == sizeof p;
  close(fds[0]);
  if (!ok) {
    waitpid(pid, nullptr, 0);
    return -1;
  }
  port = p;
  return pid;
}

class DeviceWalkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_device_walk_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    bundle_ = model::Bundle::open(testing::write_two_room_bundle((dir_ / "rooms.walk").string()));
    config_.path = (dir_ / "kiosk.toml").string();
    config_.bundle = (dir_ / "rooms.walk").string();
    config_.start = {102.0, 202.0, 10.0, std::nullopt, 0.0};
    config_.simulation.frame_rate = 30.0;
    config_.simulation.seconds = 3.0;
    config_.output.folder = (dir_ / "out").string();
    config_.devices.treadmill = DeviceConfig{"mock", write("t.csv", "time,speed\n0,0\n0.5,1.0\n")};
    config_.dimmer_circuits = {"B"};
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::string summary_text() const {
    std::ifstream in(dir_ / "out" / "summary.json");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
  std::unique_ptr<model::Bundle> bundle_;
  KioskConfig config_;
};

TEST_F(DeviceWalkTest, ModbusSimulatorKilledMidRunAndRestartedLevelsResume) {
  int port = 0;
  pid_t sim = spawn_simulator(port, 300);
  ASSERT_GT(sim, 0);
  config_.devices.dimmer_panel = modbus_device(port, {0, 1, 2, 3});
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  auto* panel = daemon.devices().modbus;
  ASSERT_NE(panel, nullptr);
  bool live = false, down = false, resumed = false;
  float level_while_down = -1.0f;
  renderer.on_draw = [&](std::size_t frame) {
    if (frame == 1) live = wait_for([&] { return panel->state() == devices::DeviceState::Live; });
    if (frame == 20) {
      kill(sim, SIGKILL);
      waitpid(sim, nullptr, 0);
      down = wait_for([&] { return panel->state() == devices::DeviceState::Down; });
    }
    if (frame == 40) level_while_down = renderer.levels.at(1);
    if (frame == 50) {
      sim = spawn_simulator(port, 800);  // same port, new level
      resumed = sim > 0 && wait_for([&] {
                  auto r = panel->poll(0);
                  return r && r->levels[0] == 0.8;
                });
    }
  };
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  const auto logged = panel->faults().logged();  // before the final kill below starts a new episode
  if (sim > 0) {
    kill(sim, SIGKILL);
    waitpid(sim, nullptr, 0);
  }
  EXPECT_TRUE(live);
  EXPECT_TRUE(down);
  EXPECT_TRUE(resumed);
  EXPECT_EQ(s.frames, 90u);                      // kept rendering through the outage
  EXPECT_FLOAT_EQ(level_while_down, 0.3f);       // last good level held while the panel was gone
  EXPECT_FLOAT_EQ(renderer.levels.at(1), 0.8f);  // circuit B follows the restarted panel
  EXPECT_EQ(s.device_states.back(), (std::pair<std::string, std::string>{"dimmer_panel", "live"}));
  EXPECT_GT(s.device_faulty_frames.back().second, 0u);
  EXPECT_EQ(logged, 1u);  // one warning for the outage, however many retries
}

TEST_F(DeviceWalkTest, ConfigNamingMissingDevicesStillWalksTheWholeRun) {
  DeviceConfig hid;
  hid.backend = "hid";
  hid.hid.path = (dir_ / "hidraw-missing").string();
  hid.hid.layout.report_id = 1;
  hid.hid.layout.length = 3;
  hid.hid.layout.fields = {{"speed", 1, 2, false, false, 0.001, 0.0, 0.0, 5.0}};
  config_.devices.treadmill = hid;
  DeviceConfig gpio;
  gpio.backend = "gpio";
  gpio.buttons.chip = "gpiochip-walk-missing";
  gpio.buttons.lines = {{devices::Button::ReturnToStart, 3}};
  config_.devices.buttons = gpio;
  auto sim = devices::PanelSimulator::tcp("127.0.0.1", 0, 4);
  const int closed_port = sim->port();
  sim.reset();
  config_.devices.dimmer_panel = modbus_device(closed_port, {0});
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  EXPECT_EQ(s.stopped_by, "end");
  EXPECT_EQ(s.frames, 90u);
  EXPECT_EQ(s.distance, 0.0);                    // treadmill down: standing still
  EXPECT_FLOAT_EQ(renderer.levels.at(1), 0.5f);  // panel never answered: circuit B keeps its default
  for (const auto& [role, state] : s.device_states) EXPECT_EQ(state, "down") << role;
  EXPECT_NE(daemon.device_status().find("treadmill down"), std::string::npos) << daemon.device_status();
  EXPECT_NE(summary_text().find("\"dimmer_panel\": \"down\""), std::string::npos) << summary_text();
}

TEST_F(DeviceWalkTest, ReturnToStartButtonPutsTheWalkerBack) {
  config_.devices.buttons = DeviceConfig{"mock", write("b.csv", "time,button\n2.0,0\n")};
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  EXPECT_EQ(s.returns_to_start, 1u);
  EXPECT_GT(s.distance, 2.0);                // it walked 1.5 m before the press and on after it
  EXPECT_NEAR(s.final_feet.x, 103.0, 0.05);  // 1 s of walking since the press at 2 s
}

TEST_F(DeviceWalkTest, NextBuildingButtonEndsTheRunForWalkdToSwitch) {
  config_.devices.buttons = DeviceConfig{"mock", write("b.csv", "time,button\n1.0,1\n")};
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  EXPECT_EQ(s.stopped_by, "next_building");
  EXPECT_LT(s.frames, 40u);
}

TEST_F(DeviceWalkTest, ReloadAppliesTheNewConfigWithoutRestartingTheWalk) {
  config_.devices.dimmer_panel = DeviceConfig{"mock", write("d.csv", "time,ch0\n0,0.25\n")};
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  std::atomic<bool> reload{false};
  KioskConfig next = config_;
  next.dimmer_circuits = {"A"};  // the operator rewired channel 0 to circuit A
  next.walker.eye_height = 1.5;
  int loads = 0;
  daemon.set_reloader(reload, [&] {
    ++loads;
    return next;
  });
  double x_before = 0.0;
  renderer.on_draw = [&](std::size_t frame) {
    if (frame == 45) {
      x_before = renderer.views.back().eye.x;
      reload = true;
    }
  };
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  EXPECT_EQ(loads, 1);
  EXPECT_EQ(s.reloads, 1u);
  EXPECT_GT(x_before, 0.5);
  EXPECT_GT(renderer.views.back().eye.x, x_before);  // walked on from where it was, not from the start
  EXPECT_NEAR(renderer.views.back().eye.z, 0.29 + 1.5, 1e-5);
  EXPECT_FLOAT_EQ(renderer.levels.at(0), 0.25f);  // channel 0 now drives A
  EXPECT_EQ(s.frames, 90u);
}

TEST_F(DeviceWalkTest, ReloadWithABadConfigKeepsTheRunningOne) {
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  std::atomic<bool> reload{false};
  daemon.set_reloader(reload, [&]() -> KioskConfig { throw Error("kiosk.toml:3: bad"); });
  renderer.on_draw = [&](std::size_t frame) {
    if (frame == 10) reload = true;
  };
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  EXPECT_EQ(s.reloads, 0u);
  EXPECT_EQ(s.frames, 90u);
  EXPECT_EQ(daemon.config().dimmer_circuits, (std::vector<std::string>{"B"}));
}

// The must-show run: the sample house, scripted treadmill and head traces, the Modbus panel simulator, and
// frames rendered through OSMesa. The walker goes through the door of hall 5642 into 5627 and stops; then
// 5627's register goes from 0 to full scale and the frame gets brighter.
TEST(HouseModbusWalk, WalksThroughTheDoorAndAPanelRegisterBrightensThatRoom) {
  const fs::path dir = fs::temp_directory_path() / ("walk_house_modbus_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bundle_path = (dir / "house.walk").string();
  compiler::compile_to_file(WALK_SOURCE_DIR "/config/scenes/house.toml", bundle_path, true);
  auto sim = devices::PanelSimulator::tcp("127.0.0.1", 0, 4);
  for (int r = 0; r < 4; ++r) sim->set_register(r, r == 1 ? 0 : 1000);  // 5627 dark at first

  KioskConfig config = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/demo.toml");
  config.bundle = bundle_path;
  config.output.folder = (dir / "out").string();
  config.output.png_every = 0;
  config.simulation.frame_rate = 10;
  config.simulation.seconds = 8;
  auto write = [&](const char* name, const char* text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  config.devices.treadmill = DeviceConfig{"mock", write("t.csv", "time,speed\n0,0\n0.6,1\n5.3,0\n")};
  config.devices.head_tracker = DeviceConfig{"mock", write("h.csv", "time,yaw_deg,pitch_deg\n0,0,-5\n")};
  config.devices.dimmer_panel = modbus_device(sim->port(), {0, 1, 2, 3});
  const auto bundle = model::Bundle::open(bundle_path);
  std::uint32_t circuit_5627 = 0;
  for (std::uint32_t c = 0; c < bundle->circuits().size(); ++c)
    if (bundle->string(bundle->circuits()[c].name) == "5627") circuit_5627 = c;

  testing::GlProbeRenderer renderer(*bundle, 160, 90);
  Daemon daemon(config, *bundle, renderer, open_devices(config.devices));
  auto* panel = daemon.devices().modbus;
  bool live = false, seen = false;
  renderer.on_draw = [&](std::size_t frame) {
    if (frame == 1) live = wait_for([&] { return panel->reads() > 0; });
    if (frame == 65) {  // t = 6.4 s: standing in 5627 since 5.3 s
      sim->set_register(1, 1000);
      seen = wait_for([&] {
        auto r = panel->poll(0);
        return r && r->levels[1] == 1.0;
      });
    }
  };
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  ASSERT_TRUE(live);
  ASSERT_TRUE(seen);
  EXPECT_EQ(s.room_sequence, (std::vector<std::string>{"5642", "5627"}));
  EXPECT_EQ(s.final_room, "5627");
  // Through the door into the next cell of the compiled partition, not only the next room.
  EXPECT_GE(s.cells_visited.size(), 2u);
  ASSERT_EQ(renderer.brightness.size(), 80u);
  const double before = renderer.brightness[63], after = renderer.brightness[79];
  EXPECT_FLOAT_EQ(renderer.levels.at(circuit_5627), 1.0f);
  EXPECT_GT(after, before + 5.0) << "mean brightness before " << before << ", after " << after;
  EXPECT_DOUBLE_EQ(renderer.brightness[62], renderer.brightness[63]);  // standing still: same frame
  fs::remove_all(dir);
}

}  // namespace device_walk_test
}  // namespace walk::kiosk
