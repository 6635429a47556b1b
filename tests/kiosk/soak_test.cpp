// A kiosk runs for months: 24 simulated hours of walkd's loop in a few minutes of wall time, with the real GL
// renderer (OSMesa), a real Modbus panel (libmodbus on loopback) driven in simulated time, a dimmer sweep
// that changes the light every frame, a wandering treadmill and head tracker, a PNG every simulated hour, and
// a panel fault every few simulated minutes (the server crashes, or sends garbage). Asserts flat memory after
// warm-up, that the light follows the panel on every frame outside a fault and its recovery, and a clean
// stop. The RSS curve is written to <build>/soak_rss.csv. WALK_SOAK_HOURS shortens or lengthens the run.
#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "devices/modbus/modbus_panel.hpp"
#include "devices/sim/panel_simulator.hpp"
#include "firmware-host/daemon.hpp"
#include "model/error.hpp"
#include "two_room_kiosk.hpp"

namespace walk::kiosk {
namespace soak_test {  // named, not anonymous: the suite compiles as unity batches

constexpr double kFrameRate = 4.0;          // simulated frames a second: 345,600 frames in a day
constexpr double kFaultEvery = 300.0;       // a panel fault every 5 simulated minutes ...
constexpr double kFaultLasts = 30.0;        // ... lasting half a minute
constexpr double kWarmUp = 3600.0;          // memory is compared with its value after the first hour
constexpr double kRssGrowthAllowed = 0.05;  // live memory (RSS after malloc_trim) within 5% of its warm value
constexpr double kRawRssGrowthAllowed = 0.10;  // RSS as is: also what the allocator keeps cached
constexpr double kSampleEvery = 600.0;         // an RSS row every 10 simulated minutes
constexpr int kFullScale = 1000;               // register value of level 1.0

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0, resident = 0.0;
  statm >> pages >> resident;
  return resident * double(sysconf(_SC_PAGESIZE));
}

double simulated_hours() {
  const char* env = std::getenv("WALK_SOAK_HOURS");
  return env ? std::max(1.5, std::atof(env)) : 24.0;
}

// The sweep the operator's panel plays: both channels in slow waves, a different level every frame.
std::uint16_t sweep(int channel, double t) {
  const double level = 0.5 + 0.45 * std::sin(2.0 * std::numbers::pi * t / 600.0 + channel * 1.3);
  return static_cast<std::uint16_t>(std::lround(level * kFullScale));
}

// Remembers the levels of the last frame, on top of the real renderer.
class LevelRecorder final : public testing::ForwardingRenderer {
 public:
  using ForwardingRenderer::ForwardingRenderer;
  void set_dimmers(std::span<const float> l) override {
    levels.assign(l.begin(), l.end());
    ForwardingRenderer::set_dimmers(l);
  }
  std::vector<float> levels;
};

using SoakTest = testing::TwoRoomKioskTest;

TEST_F(SoakTest, DayOfFaultsAndDimmerSweepsKeepsMemoryFlatAndLightOnTime) {
  const double hours = simulated_hours();
  const double seconds = hours * 3600.0;
  std::unique_ptr<FrameRenderer> gl = osmesa_renderer(64, 36);
  if (!gl) GTEST_SKIP() << osmesa_missing_;
  LevelRecorder renderer(std::move(gl));

  // A treadmill that turns to a new heading every 20 s (the walker wanders, slides along walls and crosses
  // the door now and then), and a head that sways; both as long traces, read once at start.
  std::ostringstream treadmill("time,speed,steering_deg\n", std::ios::ate);
  std::ostringstream head("time,yaw_deg,pitch_deg,x_m,y_m,z_m\n", std::ios::ate);
  for (int i = 0; i * 20.0 <= seconds; ++i) treadmill << i * 20.0 << ",1.0," << (i * 137) % 360 << "\n";
  for (int i = 0; i * 10.0 <= seconds; ++i)
    head << i * 10.0 << "," << 10.0 * std::sin(i * 0.7) << "," << 5.0 * std::cos(i * 0.3) << ","
         << 0.05 * std::sin(i * 0.5) << ",0," << 0.02 * std::cos(i * 0.9) << "\n";
  config_.devices.treadmill = DeviceConfig{"mock", write("treadmill.csv", treadmill.str())};
  config_.devices.head_tracker = DeviceConfig{"mock", write("head.csv", head.str())};
  config_.simulation.frame_rate = kFrameRate;
  config_.simulation.seconds = seconds;
  config_.output.png_every = 3600.0;
  config_.dimmer_circuits = {"A", "B"};

  // The panel: a libmodbus server on loopback, polled once a frame in simulated time (no reader thread), so
  // a crash, the reconnect backoff and staleness all run on the daemon's clock.
  auto server = devices::PanelSimulator::tcp("127.0.0.1", 0, 2);
  const int port = server->port();
  double sim_now = 0.0;
  devices::ModbusPanelConfig panel_config;
  panel_config.port = port;
  panel_config.registers = {0, 1};
  panel_config.full_scale = kFullScale;
  panel_config.timeout = 0.5;  // loopback answers in microseconds; generous for a loaded CI machine
  panel_config.retries = 0;
  auto panel = std::make_unique<devices::ModbusDimmerPanel>(panel_config, [&] { return sim_now; });
  devices::ModbusDimmerPanel& modbus = *panel;
  DeviceSet devices = open_devices(config_.devices);
  devices.dimmer_panel = std::move(panel);
  devices.modbus = &modbus;

  Daemon daemon(config_, *bundle_, renderer, std::move(devices));

  // A crash recovers within the reconnect backoff's ceiling plus a poll; garbage on the next good read.
  const double recovery = panel_config.faults.retry_max + 2.0 / kFrameRate;
  std::uint16_t shown[2] = {0, 0};  // the registers the previous frame read
  std::uint64_t late_frames = 0, checked_frames = 0, episodes = 0;
  double fault_until = -1.0, settled_after = 0.0, next_fault = kFaultEvery, next_sample = 0.0;
  bool crash = true;
  double warm_rss = 0.0, max_rss_after_warm_up = 0.0, warm_raw = 0.0, max_raw_after_warm_up = 0.0;
  const auto wall_start = std::chrono::steady_clock::now();
  std::ofstream csv(std::string(WALK_BINARY_DIR) + "/soak_rss.csv");
  csv << "simulated_hours,wall_seconds,rss_mib,rss_trimmed_mib,frames,panel_faults,late_frames\n";

  daemon.set_frame_hook([&](double now) {
    // The previous frame drew with the levels its poll read, unless a fault or its recovery was running.
    if (now > settled_after && now > 1.0) {
      ++checked_frames;
      const auto& l = renderer.levels;
      if (l.size() != 2 || std::abs(l[0] - shown[0] / double(kFullScale)) > 1e-6 ||
          std::abs(l[1] - shown[1] / double(kFullScale)) > 1e-6)
        ++late_frames;
    }
    sim_now = now;
    if (now >= next_fault) {  // a fault starts: the server crashes, or answers garbage
      ++episodes;
      fault_until = now + kFaultLasts;
      settled_after = fault_until + (crash ? recovery : 1.0 / kFrameRate);
      if (crash) server.reset();
      next_fault += kFaultEvery;
    }
    if (fault_until >= 0.0 && now >= fault_until) {  // it ends: a fresh server on the same port
      if (!server) server = devices::PanelSimulator::tcp("127.0.0.1", port, 2);
      fault_until = -1.0;
      crash = !crash;
    }
    const bool garbage = fault_until >= 0.0 && !crash;
    for (int ch = 0; ch < 2; ++ch) {
      shown[ch] = sweep(ch, now);
      if (server) server->set_register(ch, garbage && ch == 0 ? 5 * kFullScale : shown[ch]);
    }
    modbus.step();

    if (now >= next_sample) {
      // Raw RSS moves by a megabyte or two as glibc keeps or returns freed pages (thread arenas of the
      // restarted panel server, the PNG buffers); after malloc_trim it is the memory still in use, which is
      // what grows if something leaks.
      const double raw = resident_bytes();
      malloc_trim(0);
      const double rss = resident_bytes();
      if (now >= kWarmUp && warm_rss == 0.0) {
        warm_rss = rss;
        warm_raw = raw;
      }
      if (warm_rss > 0.0) {
        max_rss_after_warm_up = std::max(max_rss_after_warm_up, rss);
        max_raw_after_warm_up = std::max(max_raw_after_warm_up, raw);
      }
      csv << now / 3600.0 << ","
          << std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count() << ","
          << raw / (1024.0 * 1024.0) << "," << rss / (1024.0 * 1024.0) << ","
          << std::llround(now * kFrameRate) << "," << modbus.faults().faults() << "," << late_frames << "\n";
      next_sample += kSampleEvery;
    }
  });

  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);
  csv.close();

  EXPECT_EQ(s.stopped_by, "end");
  EXPECT_EQ(s.frames, std::uint64_t(std::llround(seconds * kFrameRate)));  // no frame skipped
  EXPECT_NEAR(s.simulated_seconds, seconds, 1.0);
  EXPECT_GE(episodes, std::uint64_t(seconds / kFaultEvery) - 1);
  EXPECT_GE(modbus.faults().faults(), episodes);  // every episode was seen as a fault ...
  EXPECT_EQ(late_frames, 0u) << "of " << checked_frames << " frames outside faults";  // ... and only then
  EXPECT_GT(checked_frames, std::uint64_t(0.7 * seconds * kFrameRate));
  EXPECT_EQ(s.frames_saved, std::uint64_t(std::ceil(seconds / 3600.0)));
  EXPECT_EQ(s.frames_not_saved, 0u);
  EXPECT_GT(s.distance, 1000.0);  // it walked all day
  // The latest rooms are kept, never more than the cap; a day (the default) walks past it. A shorter
  // WALK_SOAK_HOURS run may not reach it.
  EXPECT_EQ(s.room_sequence.size(), std::min<std::uint64_t>(s.room_changes, Summary::kRoomSequenceKept));
  if (hours >= 24.0) {
    EXPECT_GT(s.room_changes, Summary::kRoomSequenceKept);
  }
  // Flat memory: nothing grows with frames, faults, room changes, saves or latency samples.
  ASSERT_GT(warm_rss, 0.0);
  EXPECT_LE(max_rss_after_warm_up, warm_rss * (1.0 + kRssGrowthAllowed))
      << "RSS grew from " << warm_rss / 1048576.0 << " MiB to " << max_rss_after_warm_up / 1048576.0
      << " MiB; curve in soak_rss.csv";
  EXPECT_LE(max_raw_after_warm_up, warm_raw * (1.0 + kRawRssGrowthAllowed));
  std::cout << "soak: " << hours << " simulated hours, " << s.frames << " frames (" << s.frames_drawn
            << " drawn), " << episodes << " panel fault episodes, " << s.room_changes
            << " room changes, live RSS " << warm_rss / 1048576.0 << " -> max "
            << max_rss_after_warm_up / 1048576.0 << " MiB (raw " << warm_raw / 1048576.0 << " -> max "
            << max_raw_after_warm_up / 1048576.0 << "), " << s.wall_seconds << " s wall\n";
}

}  // namespace soak_test
}  // namespace walk::kiosk
