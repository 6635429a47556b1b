// Dimmer levels from raw Modbus registers, with the degenerate reads a panel can produce.
#include "devices/modbus/register_levels.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace walk::devices {
namespace register_levels_test {  // named, not anonymous: the suite compiles as unity batches

TEST(RegisterLevels, SpannedAndPerChannelReadsGiveTheSameLevels) {
  const std::vector<int> registers{10, 12, 11};
  const std::vector<std::uint16_t> span{0, 500, 1000};  // registers 10, 11, 12
  const auto a = decode_register_levels(registers, 10, true, span, 1000.0);
  ASSERT_TRUE(a.garbage.empty()) << a.garbage;
  EXPECT_EQ(a.levels, (std::vector<double>{0.0, 1.0, 0.5}));
  const std::vector<std::uint16_t> each{0, 1000, 500};
  EXPECT_EQ(decode_register_levels(registers, 0, false, each, 1000.0).levels, a.levels);
}

TEST(RegisterLevels, GarbageNamesTheChannelAndLeavesNoLevels) {
  const std::vector<int> registers{3, 4};
  const std::vector<std::uint16_t> raw{200, 1001};
  const auto above = decode_register_levels(registers, 3, true, raw, 1000.0);
  EXPECT_NE(above.garbage.find("channel 1 (register 4) = 1001"), std::string::npos) << above.garbage;
  EXPECT_TRUE(above.levels.empty());
  const auto outside = decode_register_levels(registers, 4, true, raw, 1000.0);  // register 3 before the span
  EXPECT_NE(outside.garbage.find("outside"), std::string::npos) << outside.garbage;
  const auto short_read = decode_register_levels(registers, 0, false, std::vector<std::uint16_t>{1}, 1000.0);
  EXPECT_NE(short_read.garbage.find("channel 1"), std::string::npos) << short_read.garbage;
  EXPECT_FALSE(decode_register_levels(registers, 3, true, raw, 0.0).garbage.empty()) << "zero full scale";
  // No channels: no levels, nothing wrong.
  const auto none = decode_register_levels({}, 0, true, {}, 1000.0);
  EXPECT_TRUE(none.garbage.empty() && none.levels.empty());
}

}  // namespace register_levels_test
}  // namespace walk::devices
