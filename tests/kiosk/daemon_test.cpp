#include "firmware-host/daemon.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fake_renderer.hpp"
#include "firmware-host/stop_signal.hpp"
#include "model/error.hpp"
#include "test_bundle.hpp"
#include "two_room_kiosk.hpp"

namespace walk::kiosk {
namespace daemon_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class DaemonTest : public testing::TwoRoomKioskTest {
 protected:
  void SetUp() override {
    TwoRoomKioskTest::SetUp();
    config_.simulation.seconds = 5.0;
    config_.devices.treadmill = DeviceConfig{"mock", write("t.csv", "time,speed\n0,0\n0.5,1.0\n4.5,0\n")};
    config_.devices.head_tracker = DeviceConfig{"mock", write("h.csv", "time,yaw_deg,pitch_deg\n0,0,-5\n")};
    config_.devices.dimmer_panel = DeviceConfig{"mock", write("d.csv", "time,ch0\n0,0.0\n2,0.75\n")};
    config_.dimmer_circuits = {"B"};
  }
  Summary run(testing::FakeRenderer& renderer, const std::atomic<bool>& stop) {
    Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
    return daemon.run(stop);
  }
  std::string summary_text() const {
    std::ifstream in(dir_ / "out" / "summary.json");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

TEST_F(DaemonTest, SimulatedWalkGoesThroughTheDoorAndWritesASummary) {
  config_.display.mode = "hmd";  // the head's pitch tilts the view (a fixed screen's does not)
  testing::FakeRenderer renderer;
  std::atomic<bool> stop{false};
  const Summary s = run(renderer, stop);
  EXPECT_EQ(s.mode, "simulated");
  EXPECT_EQ(s.stopped_by, "end");
  EXPECT_EQ(s.frames, 150u);
  EXPECT_EQ(renderer.views.size(), 150u);
  EXPECT_NEAR(s.simulated_seconds, 5.0, 1e-9);
  EXPECT_NEAR(s.distance, 4.0, 0.04);  // 4 s at 1 m/s, frame-quantised
  EXPECT_NEAR(s.final_feet.x, 106.0, 0.04);
  EXPECT_NEAR(s.final_feet.z, 10.29, 1e-5);  // stepped up the sill into room B
  EXPECT_EQ(s.rooms_visited, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(s.room_sequence, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(s.cells_visited, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(s.final_room, "B");
  // Eye height above the floor, pitch from the head tracker, dimmer channel 0 -> circuit "B" (index 1).
  EXPECT_NEAR(renderer.views.back().eye.z, 0.29 + config_.walker.eye_height, 1e-5);
  EXPECT_LT(renderer.views.back().forward.z, 0.0);
  ASSERT_EQ(renderer.levels.size(), 2u);
  EXPECT_FLOAT_EQ(renderer.levels[0], 1.0f);  // default level of circuit A
  EXPECT_FLOAT_EQ(renderer.levels[1], 0.75f);
  const auto json = summary_text();
  EXPECT_NE(json.find("\"frames\": 150"), std::string::npos) << json;
  EXPECT_EQ(nlohmann::json::parse(json).at("rooms_visited"), nlohmann::json::array({"A", "B"})) << json;
}

TEST_F(DaemonTest, TwoSimulatedRunsEndAtTheSamePlace) {
  config_.devices.head_tracker =
      DeviceConfig{"mock", write("h2.csv", "time,yaw_deg\n0,0\n1,20\n2,-35\n3,90\n")};
  testing::FakeRenderer r1, r2;
  std::atomic<bool> stop{false};
  const Summary a = run(r1, stop);
  const Summary b = run(r2, stop);
  EXPECT_EQ(a.final_feet, b.final_feet);
  EXPECT_EQ(a.distance, b.distance);
  EXPECT_EQ(a.frames, b.frames);
  ASSERT_EQ(r1.views.size(), r2.views.size());
  for (std::size_t i = 0; i < r1.views.size(); ++i) ASSERT_EQ(r1.views[i].eye, r2.views[i].eye) << i;
}

TEST_F(DaemonTest, StopFlagEndsTheRunCleanlyWithASummary) {
  testing::FakeRenderer renderer;
  std::atomic<bool> stop{false};
  renderer.on_draw = [&](std::size_t frames) {
    if (frames == 10) stop = true;
  };
  const Summary s = run(renderer, stop);
  EXPECT_EQ(s.stopped_by, "signal");
  EXPECT_EQ(s.frames, 10u);
  EXPECT_NE(summary_text().find("\"stopped_by\": \"signal\""), std::string::npos);
}

TEST_F(DaemonTest, SigtermStopsTheLoop) {
  install_stop_handlers();
  stop_flag() = false;
  testing::FakeRenderer renderer;
  renderer.on_draw = [](std::size_t frames) {
    if (frames == 7) std::raise(SIGTERM);
  };
  const Summary s = run(renderer, stop_flag());
  stop_flag() = false;
  EXPECT_EQ(s.stopped_by, "signal");
  EXPECT_EQ(s.frames, 7u);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "summary.json"));
}

TEST_F(DaemonTest, SavesAFrameEveryNSimulatedSeconds) {
  config_.output.png_every = 2.0;
  testing::FakeRenderer renderer;
  std::atomic<bool> stop{false};
  const Summary s = run(renderer, stop);
  EXPECT_EQ(s.frames_saved, 3u);  // t = 0, 2, 4
  EXPECT_EQ(s.frames_not_saved, 0u);
  EXPECT_EQ(renderer.captures, 3u);
  for (const char* name : {"frame_000000.png", "frame_000001.png", "frame_000002.png"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / name)) << name;  // written by the saver thread, flushed at the end
  EXPECT_FALSE(fs::exists(dir_ / "out" / "frame_000000.png.part"));
}

TEST_F(DaemonTest, UnknownCircuitAndBadStartAreReportedWithTheirKeys) {
  testing::FakeRenderer renderer;
  config_.dimmer_circuits = {"B", "kitchen"};
  try {
    Daemon d(config_, *bundle_, renderer, {});
    FAIL() << "expected an error";
  } catch (const walk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("dimmers.channels[1]"), std::string::npos) << e.what();
  }
  config_.dimmer_circuits = {};
  config_.start.x = 150.0;
  try {
    Daemon d(config_, *bundle_, renderer, {});
    FAIL() << "expected an error";
  } catch (const walk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("start"), std::string::npos) << e.what();
  }
}

TEST_F(DaemonTest, WalkerWithoutDevicesStandsStill) {
  testing::FakeRenderer renderer;
  std::atomic<bool> stop{false};
  config_.dimmer_circuits = {};
  Daemon daemon(config_, *bundle_, renderer, {});
  const Summary s = daemon.run(stop);
  EXPECT_EQ(s.distance, 0.0);
  EXPECT_EQ(s.final_feet, glm::dvec3(102, 202, 10));
}

// The real renderer with adaptive refinement, as walkd runs it: while the walker stands still the picture
// converges and then nothing is drawn (an idle kiosk); a dimmer change draws again; walking draws every
// frame.
TEST_F(DaemonTest, StillKioskStopsDrawingOnceRefinedAndDimmersWakeIt) {
  if (!osmesa_renderer(160, 90)) GTEST_SKIP() << osmesa_missing_;
  config_.simulation.seconds = 8.0;  // 240 frames
  config_.devices.treadmill = DeviceConfig{"mock", write("still.csv", "time,speed\n0,0\n")};
  std::atomic<bool> stop{false};
  // Which frames drew: how many refinement steps fit a frame depends on the machine's speed (the governor
  // times them), so the test asks when drawing happens, not how often.
  struct Recording final : testing::ForwardingRenderer {
    using ForwardingRenderer::ForwardingRenderer;
    bool draw(const render::View& v) override {
      drew.push_back(ForwardingRenderer::draw(v));
      return drew.back();
    }
    std::vector<bool> drew;
  };
  auto run_still = [&](const std::string& dimmer_trace) {
    config_.devices.dimmer_panel = DeviceConfig{"mock", write("dimmers.csv", dimmer_trace)};
    Recording fresh(make_gl_renderer(*bundle_, display_));
    Daemon still(config_, *bundle_, fresh, open_devices(config_.devices));
    const Summary s = still.run(stop);
    EXPECT_EQ(s.frames_drawn, std::size_t(std::count(fresh.drew.begin(), fresh.drew.end(), true)));
    return fresh.drew;
  };
  auto drawn_in = [](const std::vector<bool>& drew, std::size_t first, std::size_t last) {
    return std::count(drew.begin() + std::ptrdiff_t(first), drew.begin() + std::ptrdiff_t(last), true);
  };
  const std::vector<bool> steady = run_still("time,ch0\n0,0.5\n");
  const std::vector<bool> relit = run_still("time,ch0\n0,0.5\n6,0.75\n");
  ASSERT_EQ(steady.size(), 240u);
  ASSERT_EQ(relit.size(), 240u);
  // One moving frame, the refinement steps (diagonals, subdivision, samples as the governor fits them per
  // frame), then nothing: the converged picture stays on screen.
  EXPECT_TRUE(steady[0]);
  EXPECT_GE(drawn_in(steady, 0, 120), 3);
  EXPECT_EQ(drawn_in(steady, 120, 240), 0) << "a converged still view must not be drawn again";
  EXPECT_EQ(drawn_in(relit, 120, 180), 0);
  // The dimmer change at t = 6 s (frame 180) refines again from the next frame, then idles again.
  EXPECT_TRUE(relit[180]) << "a dimmer change shows in the next frame";
  EXPECT_GE(drawn_in(relit, 180, 240), 1);
  EXPECT_EQ(drawn_in(relit, 230, 240), 0) << "and converges again";

  config_.devices.treadmill = DeviceConfig{"mock", write("walk.csv", "time,speed\n0,1.0\n")};
  config_.simulation.seconds = 2.0;
  auto walking_renderer = make_gl_renderer(*bundle_, display_);
  Daemon walking(config_, *bundle_, *walking_renderer, open_devices(config_.devices));
  const Summary w = walking.run(stop);
  EXPECT_GT(w.distance, 1.0);
  EXPECT_EQ(w.frames_drawn, w.frames) << "a moving view is drawn every frame";
}

TEST(Summary, IsValidJsonWithNullsForNumbersThatAreNot) {
  Summary s;
  s.mode = "simulated";
  s.rooms_visited = {"hall \"A\"", "B"};
  s.fps = std::nan("");  // a run that drew nothing
  s.latency_p99 = std::numeric_limits<double>::infinity();
  const auto j = nlohmann::json::parse(summary_json(s));
  EXPECT_TRUE(j.at("fps").is_null());
  EXPECT_TRUE(j.at("latency_p99_ms").is_null());
  EXPECT_EQ(j.at("rooms_visited").at(0), "hall \"A\"");
  EXPECT_EQ(j.at("mode"), "simulated");
}

}  // namespace daemon_test
}  // namespace walk::kiosk
