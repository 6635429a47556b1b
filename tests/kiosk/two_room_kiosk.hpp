#pragma once
// A fixture for daemon tests on the two-room building (test_bundle.hpp): a fresh folder per test, the bundle
// written there, and a kiosk config that starts in room A facing the door (+x) at 30 simulated frames a
// second. World = local + (100, 200, 10). Tests add their own devices and run length.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "firmware-host/kiosk_config.hpp"
#include "model/bundle.hpp"
#include "test_bundle.hpp"

namespace walk::kiosk::testing {

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

  std::filesystem::path dir_;
  std::unique_ptr<model::Bundle> bundle_;
  KioskConfig config_;
};

}  // namespace walk::kiosk::testing
