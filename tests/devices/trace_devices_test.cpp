#include "devices/mock/trace_devices.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "model/error.hpp"

namespace walk::devices {
namespace trace_devices_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class TraceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("walk_trace_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // The message of the walk::Error that `f` throws, or "" when it throws nothing.
  template <typename F>
  static std::string error_of(F&& f) {
    try {
      f();
    } catch (const walk::Error& e) {
      return e.what();
    }
    return {};
  }
  fs::path dir_;
};

TEST_F(TraceTest, TreadmillReturnsNewestSampleAtOrBeforeNowWithItsOwnTime) {
  TraceTreadmill t(write("t.csv", "time,speed,steering_deg\n0.0,0.0,0\n1.0,1.2,90\n2.5,0.5,-45\n"));
  EXPECT_FALSE(t.poll(-0.1).has_value());
  auto r = t.poll(0.5);
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->time, 0.0);
  r = t.poll(1.0);
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->time, 1.0);
  EXPECT_DOUBLE_EQ(r->speed, 1.2);
  EXPECT_NEAR(r->steering, std::numbers::pi / 2, 1e-12);
  r = t.poll(100.0);  // past the end: the last sample holds
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->time, 2.5);
  EXPECT_NEAR(r->steering, -std::numbers::pi / 4, 1e-12);
}

TEST_F(TraceTest, HeadTrackerConvertsDegreesAndAllowsCommentsAndBlankLines) {
  TraceHeadTracker h(
      write("h.csv", "# recorded 2026-11-21\ntime, yaw_deg, pitch_deg\n\n0,180,-10\n0.5,-90,5\n"));
  auto r = h.poll(0.2);
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->yaw, std::numbers::pi, 1e-12);
  EXPECT_NEAR(r->pitch, -10 * std::numbers::pi / 180, 1e-12);
  r = h.poll(0.6);
  EXPECT_NEAR(r->yaw, -std::numbers::pi / 2, 1e-12);
}

TEST_F(TraceTest, DimmerPanelReportsEveryChannel) {
  TraceDimmerPanel d(write("d.csv", "time,ch0,ch1,ch2\n0,1,0.5,0\n2,0.25,0,1\n"));
  EXPECT_EQ(d.channel_count(), 3u);
  auto r = d.poll(3.0);
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->time, 2.0);
  ASSERT_EQ(r->levels.size(), 3u);
  EXPECT_DOUBLE_EQ(r->levels[0], 0.25);
  EXPECT_DOUBLE_EQ(r->levels[2], 1.0);
}

TEST_F(TraceTest, NonNumericValueNamesFileAndLine) {
  const auto path = write("bad.csv", "time,speed\n0,0\n1,fast\n");
  const auto msg = error_of([&] { TraceTreadmill t(path); });
  EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fast"), std::string::npos) << msg;
  EXPECT_NE(msg.find("speed"), std::string::npos) << msg;
}

TEST_F(TraceTest, NonIncreasingTimeNamesFileAndLine) {
  const auto path = write("time.csv", "time,yaw_deg\n0,0\n1,0\n1,5\n");
  const auto msg = error_of([&] { TraceHeadTracker h(path); });
  EXPECT_NE(msg.find(path + ":4:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("increase"), std::string::npos) << msg;
}

TEST_F(TraceTest, NegativeTimeNamesFileAndLine) {
  const auto path = write("negative.csv", "time,yaw_deg\n# starts before the walk\n-0.5,0\n1,0\n");
  const auto msg = error_of([&] { TraceHeadTracker h(path); });
  EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("negative"), std::string::npos) << msg;
}

TEST_F(TraceTest, WrongColumnCountNamesFileAndLine) {
  const auto path = write("cols.csv", "time,ch0,ch1\n0,1,1\n1,0.5\n");
  const auto msg = error_of([&] { TraceDimmerPanel d(path); });
  EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2 columns"), std::string::npos) << msg;
}

TEST_F(TraceTest, MissingFileIsNamed) {
  const auto path = (dir_ / "nope.csv").string();
  const auto msg = error_of([&] { TraceTreadmill t(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
}

TEST_F(TraceTest, HeaderProblemsAreReported) {
  EXPECT_NE(error_of([&] { TraceTreadmill t(write("a.csv", "speed,time\n")); }).find(":1:"),
            std::string::npos);
  EXPECT_NE(error_of([&] { TraceTreadmill t(write("b.csv", "time,velocity\n")); }).find("velocity"),
            std::string::npos);
  EXPECT_NE(error_of([&] { TraceTreadmill t(write("c.csv", "time,steering_deg\n")); }).find("missing column"),
            std::string::npos);
  EXPECT_NE(error_of([&] { TraceDimmerPanel d(write("d.csv", "time,ch1\n")); }).find("ch0"),
            std::string::npos);
  EXPECT_NE(error_of([&] { TraceTreadmill t(write("e.csv", "")); }).find("empty"), std::string::npos);
}

TEST_F(TraceTest, OutOfRangeValueNamesLine) {
  const auto path = write("range.csv", "time,ch0\n0,0.5\n1,1.5\n");
  const auto msg = error_of([&] { TraceDimmerPanel d(path); });
  EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
}

}  // namespace trace_devices_test
}  // namespace walk::devices
