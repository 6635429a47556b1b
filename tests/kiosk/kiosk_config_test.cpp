#include "firmware-host/kiosk_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "firmware-host/device_factory.hpp"
#include "model/error.hpp"

namespace walk::kiosk {
namespace kiosk_config_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class KioskConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("walk_kcfg_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_ / "conf");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& text) {
    const auto path = (dir_ / "conf" / "kiosk.toml").string();
    std::ofstream(path) << text;
    return path;
  }
  std::string error_of(const std::string& text) {
    try {
      (void)load_kiosk_config(write(text));
    } catch (const walk::Error& e) {
      return e.what();
    }
    return {};
  }
  fs::path dir_;
};

constexpr const char* kMinimal = "bundle = \"../b.walk\"\n[start]\nx = 1\ny = 2\n";

TEST_F(KioskConfigTest, ReadsEverySectionAndResolvesPathsAgainstTheConfigFolder) {
  const auto path = write(R"(bundle = "../build/house.walk"
[display]
backend = "osmesa"
width = 640
height = 360
fullscreen = true
[start]
x = -0.5
y = 1.5
floor_z = 2.8
heading_deg = 90
[walker]
eye_height = 1.7
step_height = 0.3
[devices.treadmill]
backend = "mock"
trace = "traces/t.csv"
[dimmers]
channels = ["5642", "5627"]
[simulation]
frame_rate = 25
seconds = 12.5
[output]
folder = "out"
png_every = 2
)");
  const auto c = load_kiosk_config(path);
  EXPECT_EQ(c.bundle, (dir_ / "build" / "house.walk").string());
  EXPECT_EQ(c.display.backend, "osmesa");
  EXPECT_EQ(c.display.width, 640);
  EXPECT_TRUE(c.display.fullscreen);
  EXPECT_DOUBLE_EQ(c.start.x, -0.5);
  EXPECT_DOUBLE_EQ(*c.start.floor_z, 2.8);
  EXPECT_FALSE(c.start.eye_z);
  EXPECT_NEAR(c.start.heading, std::numbers::pi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(c.walker.eye_height, 1.7);
  ASSERT_TRUE(c.devices.treadmill);
  EXPECT_EQ(c.devices.treadmill->trace, (dir_ / "conf" / "traces" / "t.csv").string());
  EXPECT_FALSE(c.devices.head_tracker);
  EXPECT_EQ(c.dimmer_circuits, (std::vector<std::string>{"5642", "5627"}));
  EXPECT_DOUBLE_EQ(c.simulation.seconds, 12.5);
  EXPECT_EQ(c.output.folder, (dir_ / "conf" / "out").string());
}

TEST_F(KioskConfigTest, DisplayTakesGbmAndTheRefinementKnobs) {
  const auto c = load_kiosk_config(write(std::string(kMinimal) +
                                         "[display]\nbackend = \"gbm\"\nmonitor = 1\ndrm_device = "
                                         "\"/dev/dri/card1\"\nrefine = false\ntarget_hz = 75\n"
                                         "frame_timing = \"queries\"\n"));
  EXPECT_EQ(c.display.backend, "gbm");
  EXPECT_EQ(c.display.monitor, 1);
  EXPECT_EQ(c.display.drm_device, "/dev/dri/card1");
  EXPECT_FALSE(c.display.refine);
  EXPECT_DOUBLE_EQ(c.display.target_hz, 75.0);
  EXPECT_EQ(c.display.frame_timing, "queries");
  EXPECT_FALSE(c.display.white_luminance);
  const auto lit = load_kiosk_config(write(std::string(kMinimal) + "[display]\nwhite_luminance = 150\n"));
  ASSERT_TRUE(lit.display.white_luminance);
  EXPECT_DOUBLE_EQ(*lit.display.white_luminance, 150.0);
  const auto dark = error_of(std::string(kMinimal) + "[display]\nwhite_luminance = 0\n");
  EXPECT_NE(dark.find("display.white_luminance"), std::string::npos) << dark;
  const auto msg = error_of(std::string(kMinimal) + "[display]\ntarget_hz = 0\n");
  EXPECT_NE(msg.find("display.target_hz"), std::string::npos) << msg;
  EXPECT_EQ(c.display.light_form, "compiled");
  const auto full = load_kiosk_config(write(std::string(kMinimal) + "[display]\nlight_form = \"full\"\n"));
  EXPECT_EQ(full.display.light_form, "full");
  const auto form = error_of(std::string(kMinimal) + "[display]\nlight_form = \"compact\"\n");
  EXPECT_NE(form.find("display.light_form"), std::string::npos) << form;
  EXPECT_NE(form.find("compiled"), std::string::npos) << form;
  const auto timing = error_of(std::string(kMinimal) + "[display]\nframe_timing = \"gpu\"\n");
  EXPECT_NE(timing.find("display.frame_timing"), std::string::npos) << timing;
  EXPECT_NE(timing.find("auto, finish or queries"), std::string::npos) << timing;
}

TEST_F(KioskConfigTest, MinimalConfigUsesDefaults) {
  const auto c = load_kiosk_config(write(kMinimal));
  EXPECT_EQ(c.display.backend, "auto");
  EXPECT_TRUE(c.display.refine);
  EXPECT_DOUBLE_EQ(c.display.target_hz, 60.0);
  EXPECT_DOUBLE_EQ(c.simulation.seconds, 0.0);
  EXPECT_DOUBLE_EQ(c.walker.step_height, 0.35);
}

TEST_F(KioskConfigTest, ErrorsNameFileLineAndKey) {
  auto msg = error_of(std::string(kMinimal) + "[display]\nwidth = \"wide\"\n");
  EXPECT_NE(msg.find("kiosk.toml:6: key 'display.width': expected an integer"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "[display]\nbackend = \"vulkan\"\n");
  EXPECT_NE(msg.find("display.backend"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "[walker]\neye_hieght = 1.7\n");
  EXPECT_NE(msg.find(":6: unknown key 'walker.eye_hieght'"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "[devices.treadmill]\nbackend = \"mock\"\n");
  EXPECT_NE(msg.find("devices.treadmill"), std::string::npos) << msg;
  EXPECT_NE(msg.find("trace"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "[devices.treadmill]\nbackend = \"usb\"\ntrace = \"x\"\n");
  EXPECT_NE(msg.find("devices.treadmill.backend"), std::string::npos) << msg;
  msg = error_of("bundle = \"b.walk\"\n");
  EXPECT_NE(msg.find("[start]"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "floor_z = 1\neye_z = 2\n");
  EXPECT_NE(msg.find("start.eye_z"), std::string::npos) << msg;
  msg = error_of("bundle = \n");
  EXPECT_NE(msg.find("kiosk.toml:1"), std::string::npos) << msg;
  msg = error_of(std::string(kMinimal) + "[simulation]\nframe_rate = 0\n");
  EXPECT_NE(msg.find("simulation.frame_rate': must be between"), std::string::npos) << msg;
}

TEST_F(KioskConfigTest, MissingFileIsNamed) {
  try {
    (void)load_kiosk_config((dir_ / "none.toml").string());
    FAIL();
  } catch (const walk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("none.toml"), std::string::npos);
  }
}

TEST_F(KioskConfigTest, DemoConfigAndItsTracesLoad) {
  const auto c = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/demo.toml");
  ASSERT_TRUE(c.devices.treadmill && c.devices.head_tracker && c.devices.dimmer_panel);
  const auto devices = open_devices(c.devices);
  EXPECT_GE(devices.dimmer_panel->channel_count(), c.dimmer_circuits.size());
  EXPECT_GT(c.simulation.seconds, 30.0);
}

}  // namespace kiosk_config_test
}  // namespace walk::kiosk
