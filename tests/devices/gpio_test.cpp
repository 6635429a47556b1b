// GPIO at the backend boundary: line events in, speed and button presses out.
#include <gtest/gtest.h>

#include <deque>

#include "devices/gpio/edge_filter.hpp"
#include "devices/gpio/gpio_device.hpp"

namespace walk::devices {
namespace gpio_test {  // named, not anonymous: the suite compiles as unity batches

TEST(BeltEncoder, CleanPulsesGiveDistancePerPulseOverPeriod) {
  BeltEncoder e(0.01, 0.0005, 0.5);
  for (int i = 0; i < 10; ++i) {
    e.edge(i * 0.01, true);
    e.edge(i * 0.01 + 0.005, false);
  }
  EXPECT_NEAR(e.speed(0.095), 1.0, 1e-9);  // 1 cm per 10 ms
  EXPECT_EQ(e.pulses(), 10u);
}

TEST(BeltEncoder, BounceIsFilteredOut) {
  BeltEncoder e(0.01, 0.0005, 0.5);
  for (int i = 0; i < 10; ++i) {
    const double t = i * 0.01;
    // Each closing and opening chatters: three extra edges within 60 us.
    for (double b : {0.0, 0.00002, 0.00004, 0.00006}) e.edge(t + b, b == 0.0 || b == 0.00004);
    for (double b : {0.005, 0.00502, 0.00504}) e.edge(t + b, b == 0.00502);
  }
  EXPECT_EQ(e.pulses(), 10u);
  EXPECT_GT(e.bounces(), 20u);
  EXPECT_NEAR(e.speed(0.095), 1.0, 1e-9);
}

TEST(BeltEncoder, StopsWhenPulsesStop) {
  BeltEncoder e(0.01, 0.0005, 0.5);
  for (int i = 0; i < 5; ++i) e.edge(i * 0.1, true), e.edge(i * 0.1 + 0.05, false);
  EXPECT_NEAR(e.speed(0.41), 0.1, 1e-9);
  EXPECT_EQ(e.speed(0.65), 0.0);  // more than two periods without a pulse
}

struct FakeGpio final : GpioSource {
  std::deque<std::vector<LineEvent>> batches;  // one batch per wait()
  bool fail_next = false;
  int open_failures = 0;
  std::string open() override {
    if (open_failures > 0) {
      --open_failures;
      return "gpio fake: cannot open the chip";
    }
    return {};
  }
  int wait(int, std::vector<LineEvent>& out) override {
    if (fail_next) {
      fail_next = false;
      return -1;
    }
    if (batches.empty()) return 0;
    out.insert(out.end(), batches.front().begin(), batches.front().end());
    batches.pop_front();
    return static_cast<int>(out.size());
  }
  void close() override {}
  std::string error() const override { return "No such device"; }
  std::string describe() const override { return "gpio fake"; }
};

TEST(GpioTreadmill, LineEventsWithBounceBecomeSpeed) {
  double now = 0.0;
  auto src = std::make_unique<FakeGpio>();
  auto* gpio = src.get();
  GpioEncoderConfig c;
  c.chip = "fake";
  c.line = 5;
  c.metres_per_pulse = 0.02;
  GpioTreadmill t(c, std::move(src), [&] { return now; });
  std::vector<LineEvent> batch;
  for (int i = 0; i < 8; ++i) {
    const double s = 0.02 * i;  // 20 ms period -> 1 m/s
    batch.push_back({5, true, s});
    batch.push_back({5, false, s + 0.00001});  // bounce
    batch.push_back({5, true, s + 0.00002});   // bounce
    batch.push_back({5, false, s + 0.01});
    batch.push_back({7, true, s});  // another line: ignored
  }
  gpio->batches.push_back(batch);
  t.step(0);
  now = 0.145;
  ASSERT_TRUE(t.poll(0));
  EXPECT_NEAR(t.poll(0)->speed, 1.0, 1e-9);
  EXPECT_EQ(t.pulses(), 8u);
  EXPECT_EQ(t.bounces(), 16u);
  now = 1.0;
  EXPECT_EQ(t.poll(0)->speed, 0.0);  // belt stopped: a live reading of zero
}

TEST(GpioTreadmill, ChipGoneMeansDownAndNoReadingThenRecovers) {
  double now = 0.0;
  auto src = std::make_unique<FakeGpio>();
  auto* gpio = src.get();
  GpioEncoderConfig c;
  c.chip = "fake";
  GpioTreadmill t(c, std::move(src), [&] { return now; });
  t.step(0);
  EXPECT_EQ(t.state(), DeviceState::Live);
  gpio->fail_next = true;
  t.step(0);
  EXPECT_EQ(t.state(), DeviceState::Down);
  EXPECT_FALSE(t.poll(0));
  now = 10.0;
  t.step(0);
  EXPECT_EQ(t.state(), DeviceState::Live);
}

TEST(GpioButtons, DebouncedActiveEdgesArePressesOncePerPress) {
  double now = 0.0;
  auto src = std::make_unique<FakeGpio>();
  auto* gpio = src.get();
  GpioButtonsConfig c;
  c.chip = "fake";
  c.lines = {{Button::ReturnToStart, 2}, {Button::NextBuilding, 3}};
  GpioButtons b(c, std::move(src), [&] { return now; });
  gpio->batches.push_back({{2, true, 1.000},
                           {2, false, 1.001},
                           {2, true, 1.002},   // press with bounce
                           {2, false, 1.300},  // release
                           {3, true, 2.000},
                           {3, false, 2.2},
                           {2, true, 3.0}});
  b.step(0);
  const auto presses = b.poll(0);
  ASSERT_EQ(presses.size(), 3u);
  EXPECT_EQ(presses[0].button, Button::ReturnToStart);
  EXPECT_EQ(presses[1].button, Button::NextBuilding);
  EXPECT_EQ(presses[2].button, Button::ReturnToStart);
  EXPECT_DOUBLE_EQ(presses[1].time, 2.0);
  EXPECT_TRUE(b.poll(0).empty());  // reported once
}

TEST(GpioDevice, MissingChipFailsToOpenNamingIt) {
  auto src = make_gpiod_source("gpiochip-walk-test-missing", {1}, false, "walkd-test");
  const auto why = src->open();
  EXPECT_NE(why.find("gpiochip-walk-test-missing"), std::string::npos) << why;
}

}  // namespace gpio_test
}  // namespace walk::devices
