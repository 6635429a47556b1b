// The big screen as a window: head yaw never turns the picture in screen mode, a lost tracker hands the eye
// back to the nominal position without a jump, head yaw steers only as an eased rate beyond its dead zone,
// the nominal screen shows what hmd mode shows at rest, and bad screens are refused naming the key.
#include "firmware-host/head_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "firmware-host/daemon.hpp"
#include "firmware-host/kiosk_config.hpp"
#include "model/error.hpp"
#include "render/camera.hpp"
#include "tests/kiosk/fake_renderer.hpp"
#include "tests/kiosk/test_bundle.hpp"
#include "tests/kiosk/two_room_kiosk.hpp"

namespace walk::kiosk {
namespace head_coupling_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;
constexpr double kDeg = std::numbers::pi / 180.0;

TEST(HeadCoupling, NominalScreenShowsWhatTheHeadMountedViewShowsAtRest) {
  KioskConfig c;
  c.display.width = 1280;
  c.display.height = 720;
  const glm::dvec3 feet(1.0, 2.0, 0.0);
  const double heading = 0.7;
  const render::View screen = screen_view(c, feet, heading, glm::dvec3(0.0));
  render::View hmd;
  hmd.eye = feet + glm::dvec3(0, 0, c.walker.eye_height);
  hmd.forward = {std::cos(heading), std::sin(heading), 0.0};
  hmd.fov_y_degrees = c.display.fov_y_degrees;
  const glm::mat4 a = render::view_projection(screen, 1280.0 / 720.0);
  const glm::mat4 b = render::view_projection(hmd, 1280.0 / 720.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a[i][j], b[i][j], 1e-5) << i << "," << j;
  EXPECT_NEAR(render::vertical_field_of_view(screen), c.display.fov_y_degrees * kDeg, 1e-9);
}

TEST(HeadCoupling, LostTrackingGlidesBackToTheNominalEyeWithoutAJump) {
  HeadCoupling h;
  const double dt = 1.0 / 60.0, ease = 0.5;
  const glm::dvec3 offset(0.12, -0.05, 0.03);
  for (int i = 0; i < 60; ++i) h.update(offset, dt, ease);  // tracking for a second: fully coupled
  EXPECT_NEAR(glm::length(h.eye_offset() - offset), 0.0, 1e-12);
  const double max_step = glm::length(offset) * dt / ease + 1e-12;
  glm::dvec3 previous = h.eye_offset();
  int frames_to_nominal = 0;
  while (glm::length(h.eye_offset()) > 0.0 && frames_to_nominal < 1000) {
    h.update(std::nullopt, dt, ease);
    EXPECT_LE(glm::length(h.eye_offset() - previous), max_step);
    previous = h.eye_offset();
    ++frames_to_nominal;
  }
  EXPECT_NEAR(frames_to_nominal, ease / dt, 1.0);
  // Tracking comes back: the eye glides out to it the same way.
  h.update(offset, dt, ease);
  EXPECT_LE(glm::length(h.eye_offset()), max_step);
}

TEST(HeadSteering, GlancesDoNotTurnAndTurnsBeyondTheDeadZoneEaseIn) {
  SteeringConfig c;
  c.head_turn = true;
  HeadSteering s;
  const double dt = 1.0 / 60.0;
  for (int i = 0; i < 120; ++i) s.update(c.dead_zone * 0.9, dt, c);  // a glance inside the dead zone
  EXPECT_EQ(s.turned(), 0.0);
  s.update(c.dead_zone + 20 * kDeg, dt, c);  // far beyond: the rate starts small...
  EXPECT_GT(s.rate(), 0.0);
  EXPECT_LT(s.rate(), 0.1 * c.max_turn_rate);
  for (int i = 0; i < 600; ++i) s.update(c.dead_zone + 80 * kDeg, dt, c);  // ...and never passes the limit
  EXPECT_NEAR(s.rate(), c.max_turn_rate, 1e-6);
  s.update(-(c.dead_zone + 80 * kDeg), dt, c);  // looking the other way slows the turn, not flips it
  EXPECT_GT(s.rate(), 0.0);
  for (int i = 0; i < 600; ++i) s.update(std::nullopt, dt, c);  // tracker lost: the turn eases to a stop
  EXPECT_NEAR(s.rate(), 0.0, 1e-6);
  c.head_turn = false;
  s.reset();
  for (int i = 0; i < 60; ++i) s.update(80 * kDeg, dt, c);
  EXPECT_EQ(s.turned(), 0.0);
}

class ScreenModeTest : public testing::TwoRoomKioskTest {
 protected:
  void SetUp() override {
    TwoRoomKioskTest::SetUp();
    config_.simulation.seconds = 3.0;
    config_.devices.treadmill = DeviceConfig{"mock", write("t.csv", "time,speed\n0,0\n0.5,1.0\n2.5,0\n")};
  }
  std::vector<render::View> run_with_head(const std::string& trace) {
    config_.devices.head_tracker = DeviceConfig{"mock", write("h.csv", trace)};
    testing::FakeRenderer renderer;
    std::atomic<bool> stop{false};
    Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
    daemon.run(stop);
    return renderer.views;
  }
};

TEST_F(ScreenModeTest, HeadYawWithoutSteeringLeavesEveryFrameUnchanged) {
  const auto still = run_with_head("time,yaw_deg,pitch_deg\n0,0,0\n");
  const auto glance = run_with_head("time,yaw_deg,pitch_deg\n0,0,0\n0.2,30,10\n1.0,-30,-10\n2.0,30,0\n");
  ASSERT_EQ(still.size(), glance.size());
  ASSERT_EQ(still.size(), 90u);
  for (std::size_t i = 0; i < still.size(); ++i) {
    ASSERT_EQ(still[i].eye, glance[i].eye) << i;
    ASSERT_TRUE(still[i].screen && glance[i].screen) << i;
    ASSERT_EQ(*still[i].screen, *glance[i].screen) << i;
  }
  // In hmd mode the same glances turn the view (and the walk).
  config_.display.mode = "hmd";
  const auto hmd = run_with_head("time,yaw_deg,pitch_deg\n0,0,0\n0.2,30,10\n1.0,-30,-10\n2.0,30,0\n");
  EXPECT_GT(glm::length(hmd[20].forward - still[20].forward), 0.3);
}

TEST_F(ScreenModeTest, HeadPositionMovesTheEyeBehindAFixedScreen) {
  const auto rest = run_with_head("time,yaw_deg\n0,0\n");
  // 10 cm to the right and 5 cm down, from the start: the eye glides there over tracking_ease, no jump.
  const auto moved = run_with_head("time,yaw_deg,x_m,y_m,z_m\n0,0,0.1,0,-0.05\n");
  ASSERT_EQ(rest.size(), moved.size());
  // Standing still facing +x until 0.5 s: the walker's right is -y.
  const glm::dvec3 shift = moved[14].eye - rest[14].eye;
  EXPECT_NEAR(shift.x, 0.0, 1e-9);
  EXPECT_NEAR(shift.y, -0.1, 1e-9);
  EXPECT_NEAR(shift.z, -0.05, 1e-9);
  const double first_step = glm::length(glm::dvec3(0.1, 0.0, -0.05)) / (config_.display.tracking_ease * 30.0);
  EXPECT_LE(glm::length(moved[0].eye - rest[0].eye), first_step + 1e-9);
  for (std::size_t i = 0; i < rest.size(); ++i) ASSERT_EQ(*rest[i].screen, *moved[i].screen) << i;
}

TEST_F(ScreenModeTest, StereoSendsBothEyesOfEveryScreenEyeSeparationApart) {
  config_.display.stereo = "side_by_side";
  config_.display.eye_separation = 0.07;
  // Three screens of one spanning output: a front wall and two side walls angled in, 1 m ahead.
  config_.display.screens = {{{-2.2, 0.2, 0.9}, {-0.6, 1.0, 0.9}, {-2.2, 0.2, 2.1}},
                             {{-0.8, 1.0, 0.9}, {0.8, 1.0, 0.9}, {-0.8, 1.0, 2.1}},
                             {{0.6, 1.0, 0.9}, {2.2, 0.2, 0.9}, {0.6, 1.0, 2.1}}};
  config_.devices.head_tracker = DeviceConfig{"mock", write("h.csv", "time,yaw_deg\n0,0\n")};
  testing::FakeRenderer renderer;
  std::atomic<bool> stop{false};
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  daemon.run(stop);
  ASSERT_EQ(renderer.view_sets.size(), 90u);
  for (const auto& set : renderer.view_sets) {
    ASSERT_EQ(set.size(), 6u);  // screen-major, left eye then right
    for (std::size_t s = 0; s < 3; ++s) {
      const render::View& left = set[2 * s];
      const render::View& right = set[2 * s + 1];
      EXPECT_NEAR(glm::length(right.eye - left.eye), 0.07, 1e-9);
      EXPECT_NEAR(glm::dot(right.eye - left.eye, glm::dvec3(0, 1, 0)), -0.07,
                  1e-9);  // facing +x: right is -y
      ASSERT_TRUE(left.screen && right.screen);
      EXPECT_EQ(*left.screen, *right.screen);
      EXPECT_EQ(left.eye, set[0].eye);  // the same eye for every screen
    }
  }
}

TEST_F(ScreenModeTest, SideBySideStereoDrawsEachEyeIntoItsHalfOfTheOutput) {
  DisplayConfig display;
  display.backend = "osmesa";
  display.width = 320;
  display.height = 120;
  display.stereo = "side_by_side";
  display.refine = false;
  auto renderer = make_gl_renderer(*bundle_, display);
  config_.display = display;
  // The walker in room A facing the door (+x), the eyes 6.4 cm apart behind a nominal screen.
  const auto views = screen_views(config_, glm::dvec3(2.0, 2.0, 0.0), 0.0, glm::dvec3(0.0), 0.0);
  ASSERT_EQ(views.size(), 2u);
  const float lit[] = {1.0f, 1.0f};
  renderer->set_dimmers(lit);
  ASSERT_TRUE(renderer->draw_views(views));
  const render::Image both = renderer->capture();
  ASSERT_EQ(both.width, 320);
  ASSERT_EQ(both.height, 120);
  // Each half is exactly what a mono output of that eye's size shows from that eye.
  display.width = 160;
  display.stereo = "off";
  for (int eye = 0; eye < 2; ++eye) {
    auto mono = make_gl_renderer(*bundle_, display);
    mono->set_dimmers(lit);
    ASSERT_TRUE(mono->draw(views[std::size_t(eye)]));
    const render::Image alone = mono->capture();
    ASSERT_EQ(alone.width, 160);
    int differing = 0, drawn = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const std::uint8_t* half = both.pixel(x + 160 * eye, y);
        const std::uint8_t* one = alone.pixel(x, y);
        differing += half[0] != one[0] || half[1] != one[1] || half[2] != one[2];
        drawn += int(one[0]) + one[1] + one[2] > 0;
      }
    EXPECT_EQ(differing, 0) << "eye " << eye;
    EXPECT_GT(drawn, 160 * 120 / 10) << "eye " << eye << ": the room is drawn";
  }
  // And the eyes see from different places.
  int parallax = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) parallax += both.pixel(x, y)[0] != both.pixel(x + 160, y)[0];
  EXPECT_GT(parallax, 0);
}

TEST_F(ScreenModeTest, ReloadAppliesNewScreenCornersFromTheNextFrame) {
  config_.devices.head_tracker = DeviceConfig{"mock", write("h.csv", "time,yaw_deg\n0,0\n")};
  testing::FakeRenderer renderer;
  Daemon daemon(config_, *bundle_, renderer, open_devices(config_.devices));
  KioskConfig next = config_;
  next.display.screen = ScreenCorners{{-1.0, 2.0, 1.0}, {1.0, 2.0, 1.0}, {-1.0, 2.0, 2.2}};  // measured
  std::atomic<bool> reload{false};
  daemon.set_reloader(reload, [&] { return next; });
  renderer.on_draw = [&](std::size_t frame) {
    if (frame == 30) reload = true;
  };
  std::atomic<bool> stop{false};
  daemon.run(stop);
  ASSERT_EQ(renderer.views.size(), 90u);
  const auto& before = *renderer.views[29].screen;
  const auto& after = *renderer.views[31].screen;
  // Facing +x: the nominal screen is 1 m ahead, the measured one 2 m; the walker moved < 0.1 m between.
  EXPECT_NEAR(before.lower_left.x - renderer.views[29].eye.x, 1.0, 1e-9);
  EXPECT_NEAR(after.lower_left.x - renderer.views[31].eye.x, 2.0, 1e-9);
  EXPECT_NEAR(after.upper_left.z - after.lower_left.z, 1.2, 1e-9);
}

// Screens on outputs of their own: GLFW windows (under xvfb-run in CI), each its screen's view; a monitor
// that does not exist is a start-up error naming it.
TEST_F(ScreenModeTest, EachScreenOnItsOwnOutputShowsItsOwnView) {
  const char* x_display = std::getenv("DISPLAY");
  if (!x_display || !*x_display) GTEST_SKIP() << "no DISPLAY: run under xvfb-run to test several windows";
  DisplayConfig display;
  display.backend = "glfw";
  display.width = 160;
  display.height = 120;
  display.refine = false;
  display.outputs = "monitors";
  display.screens = {{{-0.8, 1.0, 1.0}, {0.8, 1.0, 1.0}, {-0.8, 1.0, 2.2}},
                     {{0.8, 1.0, 1.0}, {2.186, 0.2, 1.0}, {0.8, 1.0, 2.2}}};
  config_.display = display;
  auto renderer = make_gl_renderer(*bundle_, display);
  const auto views = screen_views(config_, glm::dvec3(2.0, 2.0, 0.0), 0.0, glm::dvec3(0.0), 0.0);
  ASSERT_EQ(views.size(), 2u);
  const float lit[] = {1.0f, 1.0f};
  renderer->set_dimmers(lit);
  ASSERT_TRUE(renderer->draw_views(views));
  renderer->present(true);
  const render::Image both = renderer->capture();
  ASSERT_EQ(both.width, 320);  // two 160-pixel windows side by side
  // Each window shows what a single output of its screen shows.
  display.outputs = "span";
  for (std::size_t screen = 0; screen < 2; ++screen) {
    display.screens = {config_.display.screens[screen]};
    display.backend = "osmesa";
    auto alone = make_gl_renderer(*bundle_, display);
    alone->set_dimmers(lit);
    ASSERT_TRUE(alone->draw(views[screen]));
    const render::Image one = alone->capture();
    int differing = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x)
        for (int k = 0; k < 3; ++k)
          differing += std::abs(int(both.pixel(x + 160 * int(screen), y)[k]) - int(one.pixel(x, y)[k])) > 1;
    EXPECT_EQ(differing, 0) << "screen " << screen;
  }
  display.backend = "glfw";
  display.fullscreen = true;
  display.monitor = 7;
  try {
    (void)make_gl_renderer(*bundle_, display);
    ADD_FAILURE() << "monitor 7 does not exist";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("monitor 7"), std::string::npos) << e.what();
  }
}

TEST(ScreenConfig, BadScreensAreRefusedNamingTheKey) {
  const fs::path dir = fs::temp_directory_path() / "walk_screen_config";
  fs::create_directories(dir);
  auto error = [&](const std::string& display) {
    const fs::path p = dir / "kiosk.toml";
    std::ofstream(p) << "bundle = \"x.walk\"\n[start]\nx = 0\ny = 0\nfloor_z = 0\n" << display;
    try {
      (void)load_kiosk_config(p.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string skew = error(
      "[display.screen]\nlower_left = [-1, 1, 1]\nlower_right = [1, 1, 1]\nupper_left = [-0.5, 1, 2]\n");
  EXPECT_NE(skew.find("key 'display.screen.upper_left': corners do not form a rectangle"), std::string::npos)
      << skew;
  const std::string fourth = error(
      "[display.screen]\nlower_left = [-1, 1, 1]\nlower_right = [1, 1, 1]\nupper_left = [-1, 1, 2]\n"
      "upper_right = [1, 1.2, 2]\n");
  EXPECT_NE(fourth.find("display.screen.upper_right"), std::string::npos) << fourth;
  const std::string behind =
      error("[display.screen]\nlower_left = [1, 1, 1]\nlower_right = [-1, 1, 1]\nupper_left = [1, 1, 2]\n");
  EXPECT_NE(behind.find("key 'display.screen': the nominal eye is not in front of the screen"),
            std::string::npos)
      << behind;
  const std::string missing = error("[display.screen]\nlower_left = [-1, 1, 1]\nupper_left = [-1, 1, 2]\n");
  EXPECT_NE(missing.find("missing key 'lower_right'"), std::string::npos) << missing;
  const std::string gbm = error("[display]\nbackend = \"gbm\"\noutputs = \"monitors\"\n");
  EXPECT_NE(gbm.find("key 'display.outputs': \"monitors\" needs backend = \"glfw\""), std::string::npos)
      << gbm;
  const std::string mode = error("[display]\nmode = \"cave\"\n");
  EXPECT_NE(mode.find("key 'display.mode': unknown mode 'cave'"), std::string::npos) << mode;
  const std::string good = error(
      "[display]\nmode = \"screen\"\nnominal_eye = [0, 0, 1.7]\n[display.screen]\nlower_left = [-1, 1, 1]\n"
      "lower_right = [1, 1, 1]\nupper_left = [-1, 1, 2.125]\nupper_right = [1, 1, 2.125]\n");
  EXPECT_EQ(good, "");
  fs::remove_all(dir);
}

}  // namespace head_coupling_test
}  // namespace walk::kiosk
