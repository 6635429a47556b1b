// HID parsing at the backend boundary: raw report bytes in, decoded values or a named fault out.
#include <gtest/gtest.h>

#include <deque>
#include <random>

#include "devices/hid/hid_device.hpp"
#include "devices/hid/report_layout.hpp"
#include "model/error.hpp"

namespace walk::devices {
namespace hid_report_test {  // named, not anonymous: the suite compiles as unity batches

// Report 3, 7 bytes: speed u16 LE at 1 (mm/s), steering s16 LE at 3 (milliradians), flags at 5..6.
HidReportLayout treadmill_layout() {
  HidReportLayout l;
  l.report_id = 3;
  l.length = 7;
  l.fields = {{"speed", 1, 2, false, false, 0.001, 0.0, 0.0, 5.0},
              {"steering", 3, 2, true, false, 0.001, 0.0, -1.6, 1.6}};
  return l;
}

TEST(HidReport, DecodesOffsetsSizesSignednessAndScale) {
  const std::uint8_t r[] = {3, 0xd0, 0x07, 0x18, 0xfc, 0, 0};  // 2000 mm/s, -1000 mrad
  const auto d = decode_report(treadmill_layout(), r);
  ASSERT_EQ(d.status, HidDecode::Ok) << d.why;
  EXPECT_DOUBLE_EQ(d.values[0], 2.0);
  EXPECT_DOUBLE_EQ(d.values[1], -1.0);
}

TEST(HidReport, BigEndianOneAndFourByteFields) {
  HidReportLayout l;
  l.length = 6;
  l.fields = {
      {"a", 0, 1, true, false, 1.0}, {"b", 1, 4, true, true, 1.0}, {"c", 5, 1, false, false, 0.5, 1.0}};
  const std::uint8_t r[] = {0xff, 0xff, 0xff, 0xff, 0xfe, 200};
  const auto d = decode_report(l, r);
  ASSERT_EQ(d.status, HidDecode::Ok) << d.why;
  EXPECT_EQ(d.values[0], -1.0);
  EXPECT_EQ(d.values[1], -2.0);
  EXPECT_EQ(d.values[2], 101.0);
}

TEST(HidReport, TruncatedReportsAreFaultsAtEveryLength) {
  const std::uint8_t full[] = {3, 0xd0, 0x07, 0x18, 0xfc, 0, 0};
  for (std::size_t n = 0; n < sizeof full; ++n) {
    const auto d = decode_report(treadmill_layout(), std::span(full, n));
    EXPECT_EQ(d.status, HidDecode::Truncated) << n;
    EXPECT_FALSE(d.why.empty());
  }
}

TEST(HidReport, OtherReportIdsAreSkippedNotDecoded) {
  const std::uint8_t r[] = {4, 0xd0, 0x07, 0x18, 0xfc, 0, 0};
  EXPECT_EQ(decode_report(treadmill_layout(), r).status, HidDecode::OtherReport);
}

TEST(HidReport, RandomBytesNeverDecodeOutsideTheConfiguredRanges) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255), len(0, 12);
  int ok = 0, bad = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> r(static_cast<std::size_t>(len(rng)));
    for (auto& b : r) b = static_cast<std::uint8_t>(byte(rng));
    if (!r.empty() && i % 2) r[0] = 3;  // half carry the right id, so the value checks get exercised
    const auto d = decode_report(treadmill_layout(), r);
    if (d.status == HidDecode::Ok) {
      ++ok;
      EXPECT_GE(d.values[0], 0.0);
      EXPECT_LE(d.values[0], 5.0);
      EXPECT_GE(d.values[1], -1.6);
      EXPECT_LE(d.values[1], 1.6);
    } else {
      ++bad;
    }
  }
  EXPECT_GT(ok, 0);
  EXPECT_GT(bad, ok);  // most random reports are rejected by id, length or range
}

TEST(HidReport, LayoutCheckNamesTheBadField) {
  auto l = treadmill_layout();
  l.fields[1].offset = 6;
  EXPECT_NE(l.check().find("steering"), std::string::npos);
  l = treadmill_layout();
  l.fields[0].size = 3;
  EXPECT_NE(l.check().find("size 3"), std::string::npos);
  l = treadmill_layout();
  l.fields[0].offset = 0;
  EXPECT_NE(l.check().find("report id"), std::string::npos);
}

// A scripted HidSource: each read pops one entry; an empty optional is a timeout, an error entry a failure.
struct FakeHid final : HidSource {
  struct Item {
    std::vector<std::uint8_t> bytes;
    bool fail = false;
  };
  std::deque<Item> items;
  int opens = 0, fail_opens = 0;
  std::string open() override {
    ++opens;
    if (fail_opens > 0) {
      --fail_opens;
      return "no such device";
    }
    return {};
  }
  int read(std::span<std::uint8_t> buf, int) override {
    if (items.empty()) return 0;
    auto it = items.front();
    items.pop_front();
    if (it.fail) return -1;
    const auto n = std::min(buf.size(), it.bytes.size());
    std::copy_n(it.bytes.begin(), n, buf.begin());
    return static_cast<int>(n);
  }
  void close() override {}
  std::string error() const override { return "device disconnected"; }
  std::string describe() const override { return "fake hid"; }
};

struct HidTreadmillTest : ::testing::Test {
  double now = 0.0;
  FakeHid* hid = nullptr;
  std::unique_ptr<HidTreadmill> make(FaultPolicy p = {}) {
    auto src = std::make_unique<FakeHid>();
    hid = src.get();
    return std::make_unique<HidTreadmill>(std::make_unique<HidReader>(
        "treadmill (fake)", std::move(src), treadmill_layout(), p, [this] { return now; }));
  }
};

TEST_F(HidTreadmillTest, GoodReportsGarbageAndSilenceGiveLastGoodThenStandStill) {
  auto t = make();
  hid->items.push_back({{3, 0xe8, 0x03, 0, 0, 0, 0}});        // 1.0 m/s
  hid->items.push_back({{3, 0xe8}});                          // truncated
  hid->items.push_back({{3, 0xff, 0xff, 0xff, 0xff, 0, 0}});  // 65.5 m/s: garbage
  t->reader().step(0);
  ASSERT_TRUE(t->poll(0));
  EXPECT_DOUBLE_EQ(t->poll(0)->speed, 1.0);
  now = 0.1;
  t->reader().step(0);
  t->reader().step(0);
  EXPECT_DOUBLE_EQ(t->poll(0)->speed, 1.0);  // garbage ignored, last good kept
  EXPECT_EQ(t->reader().faults().faults(), 2u);
  EXPECT_EQ(t->reader().faults().logged(), 1u);  // one episode, one line
  now = 1.0;                                     // silence past stale_after
  t->reader().step(0);
  EXPECT_EQ(t->state(), DeviceState::Stale);
  EXPECT_FALSE(t->poll(0));  // the daemon treats this as standing still
}

TEST_F(HidTreadmillTest, DisappearsAndComesBackWithBackoff) {
  FaultPolicy p;
  p.retry_min = 0.5;
  p.retry_max = 2.0;
  auto t = make(p);
  hid->items.push_back({{3, 0xe8, 0x03, 0, 0, 0, 0}});
  hid->items.push_back({{}, true});  // unplugged
  t->reader().step(0);
  t->reader().step(0);
  EXPECT_EQ(t->state(), DeviceState::Down);
  EXPECT_FALSE(t->poll(0));
  hid->fail_opens = 3;
  const int opens_before = hid->opens;
  for (int i = 0; i < 40; ++i) {  // 4 s of 0.1 s steps: reopen at +0.5, +1.5 (1 s), +3.5 (2 s)
    now += 0.1;
    t->reader().step(0);
  }
  EXPECT_EQ(hid->opens - opens_before, 3);  // backoff, not a retry every step
  EXPECT_DOUBLE_EQ(t->reader().faults().retry_delay(), 2.0);
  now += 2.0;
  hid->items.push_back({{3, 0xd0, 0x07, 0, 0, 0, 0}});
  t->reader().step(0);
  EXPECT_EQ(t->state(), DeviceState::Live);
  EXPECT_DOUBLE_EQ(t->poll(0)->speed, 2.0);
}

TEST_F(HidTreadmillTest, RandomReportStreamNeverYieldsAnOutOfRangeReading) {
  auto t = make();
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> byte(0, 255), len(0, 9);
  for (int i = 0; i < 3000; ++i) {
    std::vector<std::uint8_t> r(static_cast<std::size_t>(len(rng)));
    for (auto& b : r) b = static_cast<std::uint8_t>(byte(rng));
    if (!r.empty()) r[0] = 3;
    hid->items.push_back({r});
    now += 0.001;
    t->reader().step(0);
    if (auto rd = t->poll(0)) {
      ASSERT_GE(rd->speed, 0.0);
      ASSERT_LE(rd->speed, 5.0);
      ASSERT_LE(std::abs(rd->steering), 1.6);
    }
  }
  EXPECT_GT(t->reader().reports(), 0u);
  EXPECT_LT(t->reader().faults().logged(), 60u);  // rate-limited, not a line per bad report
}

TEST(HidDevice, MissingRequiredFieldIsAConfigError) {
  HidReportLayout l;
  l.length = 2;
  l.fields = {{"pitch", 0, 1}};
  auto reader =
      std::make_unique<HidReader>("head tracker (fake)", std::make_unique<FakeHid>(), l, FaultPolicy{});
  try {
    HidHeadTracker h(std::move(reader));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'yaw'"), std::string::npos) << e.what();
  }
}

TEST(HidDevice, HidapiSourceOnAMissingPathFailsToOpenWithAHint) {
  HidDeviceConfig c;
  c.path = "/dev/hidraw-walk-test-missing";
  auto src = make_hidapi_source(c);
  const auto why = src->open();
  EXPECT_NE(why.find("/dev/hidraw-walk-test-missing"), std::string::npos) << why;
}

}  // namespace hid_report_test
}  // namespace walk::devices
