// End to end: compile the sample house with the real pipeline, then walk the demo traces through it with the
// daemon (fake renderer: this checks the walk, not the pixels) and, when walkd is built, with the real
// binary.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "compiler/pipeline.hpp"
#include "fake_renderer.hpp"
#include "firmware-host/daemon.hpp"

namespace walk::kiosk {
namespace house_walk_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class HouseWalkTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Per process: ctest -j runs each test of this suite in its own process at the same time.
    dir_ = fs::temp_directory_path() / ("walk_house_walk_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    bundle_path_ = (dir_ / "house.walk").string();
    compiler::compile_to_file(WALK_SOURCE_DIR "/config/scenes/house.toml", bundle_path_, true);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static inline fs::path dir_;
  static inline std::string bundle_path_;
};

TEST_F(HouseWalkTest, DemoWalkPassesThroughTheDoorsIntoTheIntendedRooms) {
  KioskConfig config = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/demo.toml");
  config.bundle = bundle_path_;
  config.output.folder = (dir_ / "out").string();
  const auto bundle = model::Bundle::open(config.bundle);
  testing::FakeRenderer renderer;
  Daemon daemon(config, *bundle, renderer, open_devices(config.devices));
  std::atomic<bool> stop{false};
  const Summary s = daemon.run(stop);

  // Each room change is a pass through a door or the open passage; walls in between would stop the walker.
  EXPECT_EQ(s.room_sequence, (std::vector<std::string>{"5642", "5627", "5642", "5634", "5642", "5618"}));
  EXPECT_EQ(s.final_room, "5618");
  EXPECT_NEAR(s.final_feet.z, 2.8, 1e-3);  // stayed on the first floor
  EXPECT_GT(s.distance, 25.0);             // the whole plan was walked, not cut short by a jamb
  // Never ends inside a wall: the body circle at the final position touches nothing solid.
  const auto& nav = daemon.navigator();
  EXPECT_EQ(nav.penetration(glm::dvec2(nav.feet()), nav.feet().z), 0.0);
  // Every dimmer channel found its circuit and the sweep reached the renderer.
  EXPECT_EQ(renderer.levels.size(), bundle->circuits().size());
}

TEST_F(HouseWalkTest, RandomWalkNeverEndsAFrameInsideAWall) {
  const auto bundle = model::Bundle::open(bundle_path_);
  Navigator nav({bundle->vertices(), bundle->indices(), bundle->polygons()});
  const glm::dvec3 origin(bundle->meta().origin[0], bundle->meta().origin[1], bundle->meta().origin[2]);
  ASSERT_TRUE(nav.place(glm::dvec3(-0.585, 0.5, 2.8) - origin));
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159), seconds(0.2, 3.0);
  int room_changes = 0;
  auto room = bundle->polygons()[nav.floor_polygon()].group;
  for (int leg = 0; leg < 400; ++leg) {
    const double heading = angle(rng);
    for (int f = 0, n = static_cast<int>(seconds(rng) * 30); f < n; ++f) {
      nav.walk(1.5, heading, 1.0 / 30.0);
      ASSERT_LE(nav.penetration(glm::dvec2(nav.feet()), nav.feet().z), 1e-4) << "leg " << leg;
      ASSERT_NEAR(nav.feet().z + origin.z, 2.8, 1e-3) << "left the first floor at leg " << leg;
    }
    const auto now = bundle->polygons()[nav.floor_polygon()].group;
    room_changes += now != room;
    room = now;
  }
  EXPECT_GT(room_changes, 0);  // the random walk found a door at least once
}

TEST_F(HouseWalkTest, WalkdBinaryRunsTheDemoAndWritesFrames) {
  const std::string walkd = WALK_BINARY_DIR "/firmware-host/walkd";
  if (!fs::exists(walkd)) GTEST_SKIP() << "walkd not built";
  const auto out = dir_ / "walkd-out";
  const std::string command = walkd + " --config " WALK_SOURCE_DIR "/config/kiosk/demo.toml --bundle " +
                              bundle_path_ + " --output " + out.string() + " --simulate 6 > " +
                              (dir_ / "walkd.log").string() + " 2>&1";
  const int rc = std::system(command.c_str());
  std::ifstream log(dir_ / "walkd.log");
  std::stringstream log_text;
  log_text << log.rdbuf();
  if (rc != 0 && log_text.str().find("backend") != std::string::npos &&
      log_text.str().find("cannot") != std::string::npos)
    GTEST_SKIP() << "no GL backend here: " << log_text.str();
  ASSERT_EQ(rc, 0) << log_text.str();
  std::ifstream in(out / "summary.json");
  std::stringstream json;
  json << in.rdbuf();
  EXPECT_NE(json.str().find("\"frames\": 180"), std::string::npos) << json.str();
  EXPECT_EQ(nlohmann::json::parse(json.str()).at("rooms_visited"), nlohmann::json::array({"5642", "5627"}))
      << json.str();
  EXPECT_TRUE(fs::exists(out / "frame_000000.png"));
  EXPECT_TRUE(fs::exists(out / "frame_000001.png"));  // t = 4 s
  EXPECT_NE(log_text.str().find("room '5642' -> '5627'"), std::string::npos) << log_text.str();
}

TEST_F(HouseWalkTest, WalkdStopsCleanlyOnSigtermInRealTime) {
  const std::string walkd = WALK_BINARY_DIR "/firmware-host/walkd";
  if (!fs::exists(walkd)) GTEST_SKIP() << "walkd not built";
  const auto config = dir_ / "realtime.toml";
  const auto out = dir_ / "realtime-out";
  std::ofstream(config) << "bundle = \"" << bundle_path_ << "\"\n"
                        << "[display]\nbackend = \"auto\"\nwidth = 160\nheight = 90\n"
                        << "[start]\nx = -0.585\ny = 0.5\nfloor_z = 2.8\n"
                        << "[simulation]\nseconds = 0\n";  // real time until stopped
  const std::string log = (dir_ / "realtime.log").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string config_arg = config.string(), out_arg = out.string();
    if (!std::freopen(log.c_str(), "w", stdout) || !std::freopen(log.c_str(), "a", stderr)) _exit(126);
    execl(walkd.c_str(), "walkd", "--config", config_arg.c_str(), "--output", out_arg.c_str(), nullptr);
    _exit(127);
  }
  // Wait for the first frames (the summary's folder appears when the loop starts), then stop it like systemd.
  for (int i = 0; i < 300 && !fs::exists(out); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream log_in(log);
  std::stringstream log_text;
  log_text << log_in.rdbuf();
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && log_text.str().find("backend") != std::string::npos)
    GTEST_SKIP() << "no GL backend here: " << log_text.str();
  ASSERT_TRUE(WIFEXITED(status)) << log_text.str();
  EXPECT_EQ(WEXITSTATUS(status), 0) << log_text.str();
  std::ifstream in(out / "summary.json");
  std::stringstream json;
  json << in.rdbuf();
  EXPECT_NE(json.str().find("\"stopped_by\": \"signal\""), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("\"mode\": \"realtime\""), std::string::npos) << json.str();
}

}  // namespace house_walk_test
}  // namespace walk::kiosk
