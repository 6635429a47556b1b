#pragma once
// A fixture for daemon tests on the two-room building (test_bundle.hpp): a fresh folder per test, the bundle
// written there, and a kiosk config that starts in room A facing the door (+x) at 30 simulated frames a
// second. World = local + (100, 200, 10). Tests add their own devices and run length.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>

#include "firmware-host/frame_renderer.hpp"
#include "firmware-host/kiosk_config.hpp"
#include "model/bundle.hpp"
#include "model/error.hpp"
#include "test_bundle.hpp"

namespace walk::kiosk::testing {

// Passes every call to a real renderer; a test overrides what it watches. draw_views is left to the base,
// which calls draw with the one view these tests have, so an overridden draw sees every frame.
class ForwardingRenderer : public FrameRenderer {
 public:
  explicit ForwardingRenderer(std::unique_ptr<FrameRenderer> inner) : inner_(std::move(inner)) {}
  const char* name() const override { return inner_->name(); }
  void set_dimmers(std::span<const float> levels) override { inner_->set_dimmers(levels); }
  bool draw(const render::View& view) override { return inner_->draw(view); }
  render::Image capture() const override { return inner_->capture(); }
  void present(bool drew) override { inner_->present(drew); }

 private:
  std::unique_ptr<FrameRenderer> inner_;
};

class TwoRoomKioskTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("walk_" + std::string(test->test_suite_name()) + "_" + std::string(test->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    bundle_ = model::Bundle::open(write_two_room_bundle((dir_ / "rooms.walk").string()));
    config_.path = (dir_ / "kiosk.toml").string();
    config_.bundle = (dir_ / "rooms.walk").string();
    config_.start.x = 102.0;
    config_.start.y = 202.0;
    config_.start.floor_z = 10.0;
    config_.simulation.frame_rate = 30.0;
    config_.output.folder = (dir_ / "out").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  // The real GL renderer on OSMesa; null where OSMesa cannot start, with the reason in osmesa_missing_
  // (the caller skips: GTEST_SKIP must run in the test body).
  std::unique_ptr<FrameRenderer> osmesa_renderer(int width, int height) {
    display_.backend = "osmesa";
    display_.width = width;
    display_.height = height;
    try {
      return make_gl_renderer(*bundle_, display_);
    } catch (const Error& e) {
      osmesa_missing_ = std::string("no OSMesa here: ") + e.what();
      return nullptr;
    }
  }

  std::filesystem::path dir_;
  DisplayConfig display_;  // the last osmesa_renderer's
  std::string osmesa_missing_;
  std::unique_ptr<model::Bundle> bundle_;
  KioskConfig config_;
};

}  // namespace walk::kiosk::testing
