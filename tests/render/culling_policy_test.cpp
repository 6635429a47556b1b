// The per-cell judge of the portal walk and of occlusion culling (render/culling_policy.hpp): a cell where
// the walk hides little rests from it, a cell where it hides much keeps it, and a resting cell is measured
// again after its rest.
#include "render/culling_policy.hpp"

#include <gtest/gtest.h>

namespace walk::render {
namespace culling_policy_test {  // named, not anonymous: the suite compiles as unity batches

TEST(CullingPolicy, ACellWhereTheWalkHidesLittleRestsThenTriesAgain) {
  CullingPolicy policy(2);
  for (std::uint32_t f = 0; f < CullingPolicy::kProbeFrames; ++f) {
    ASSERT_TRUE(policy.applies(0)) << "measured over its first frames";
    policy.record(0, 10, 990);  // 1 % hidden
  }
  EXPECT_FALSE(policy.applies(0));
  EXPECT_EQ(policy.cells_resting(), 1u);
  EXPECT_TRUE(policy.applies(1)) << "cells are judged apart";
  for (std::uint32_t f = 0; f + 1 < CullingPolicy::kRestFrames; ++f) policy.rested(0);
  EXPECT_FALSE(policy.applies(0));
  policy.rested(0);
  EXPECT_TRUE(policy.applies(0)) << "after its rest the cell is measured again";
}

TEST(CullingPolicy, ACellWhereTheWalkHidesMuchKeepsIt) {
  CullingPolicy policy(1);
  for (std::uint32_t f = 0; f < 4 * CullingPolicy::kProbeFrames; ++f) policy.record(0, 300, 700);
  EXPECT_TRUE(policy.applies(0));
  // At the threshold exactly the walk is kept; just under it the cell rests.
  for (std::uint32_t f = 0; f < CullingPolicy::kProbeFrames; ++f) policy.record(0, 100, 900);
  EXPECT_TRUE(policy.applies(0));
  for (std::uint32_t f = 0; f < CullingPolicy::kProbeFrames; ++f) policy.record(0, 99, 901);
  EXPECT_FALSE(policy.applies(0));
}

TEST(CullingPolicy, EmptyFramesAndUnknownCellsKeepWalking) {
  CullingPolicy policy(1);
  for (std::uint32_t f = 0; f < CullingPolicy::kProbeFrames; ++f) policy.record(0, 0, 0);
  EXPECT_TRUE(policy.applies(0)) << "nothing drawn is no evidence against the walk";
  EXPECT_TRUE(policy.applies(7));
  policy.record(7, 0, 100);
  policy.rested(7);
}

}  // namespace culling_policy_test
}  // namespace walk::render
