#include "devices/fault.hpp"

#include <gtest/gtest.h>

namespace walk::devices {
namespace fault_test {  // named, not anonymous: the suite compiles as unity batches

TEST(FaultTracker, OneLogLinePerEpisodeThenARateLimitedSummary) {
  FaultPolicy p;
  p.log_every = 10.0;
  FaultTracker f("dev", p);
  for (int i = 0; i < 100; ++i) f.garbage(i * 0.05, "bad");  // 5 s of garbage
  EXPECT_EQ(f.faults(), 100u);
  EXPECT_EQ(f.logged(), 1u);
  f.garbage(12.0, "bad");  // past log_every: one summary line
  EXPECT_EQ(f.logged(), 2u);
  f.good(12.1);
  f.garbage(12.2, "bad");  // a new episode logs at once
  EXPECT_EQ(f.logged(), 3u);
}

TEST(FaultTracker, BackoffDoublesToTheCapAndResetsOnRecovery) {
  FaultPolicy p;
  p.retry_min = 1.0;
  p.retry_max = 4.0;
  FaultTracker f("dev", p);
  f.down(0.0, "gone");
  EXPECT_FALSE(f.may_reopen(0.9));
  EXPECT_TRUE(f.may_reopen(1.0));
  f.down(1.0, "gone");
  f.down(3.0, "gone");
  f.down(7.0, "gone");
  EXPECT_DOUBLE_EQ(f.retry_delay(), 4.0);
  EXPECT_FALSE(f.may_reopen(10.9));
  f.good(11.0);
  EXPECT_EQ(f.state(11.0), DeviceState::Live);
  EXPECT_EQ(f.state(11.0 + p.stale_after + 0.1), DeviceState::Stale);
  f.down(12.0, "gone");
  EXPECT_DOUBLE_EQ(f.retry_delay(), 1.0);
  EXPECT_EQ(f.state(12.0), DeviceState::Down);
}

}  // namespace fault_test
}  // namespace walk::devices
