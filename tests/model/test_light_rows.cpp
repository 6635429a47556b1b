#include <gtest/gtest.h>

#include <vector>

#include "model/light_rows.hpp"

namespace walk::model {
namespace test_light_rows {  // named, not anonymous: the suite compiles as unity batches

// Three rows of two circuits: the first lit by circuit 1 alone, the second by none, the third by both.
const std::vector<float> kDense{0.0f, 0.0f, 0.0f, 1.0f, 2.0f, 3.0f,  //
                                0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,  //
                                0.5f, 0.0f, 0.0f, 0.0f, 0.0f, 4.0f};

TEST(LightRows, KeepsOnlyTheCircuitsThatReachARowAndGivesTheDenseTableBack) {
  const LightRows rows = LightRows::from_dense(kDense, 2);
  ASSERT_EQ(rows.rows(), 3u);
  ASSERT_EQ(rows.entries.size(), 3u);  // four zero entries left out
  ASSERT_EQ(rows.row(0).size(), 1u);
  EXPECT_EQ(rows.row(0)[0].circuit, 1u);
  EXPECT_TRUE(rows.row(1).empty());
  ASSERT_EQ(rows.row(2).size(), 2u);
  EXPECT_EQ(rows.row(2)[0].circuit, 0u);  // a zero channel is kept where another channel is lit
  EXPECT_EQ(rows.row(2)[1].rgb[2], 4.0f);
  EXPECT_EQ(rows.dense(2), kDense);
  float sum[3];
  rows.view().sum_row(2, sum);
  EXPECT_EQ(sum[0], 0.5f);
  EXPECT_EQ(sum[2], 4.0f);
}

TEST(LightRows, NoCircuitsOrNoRowsIsEmpty) {
  EXPECT_TRUE(LightRows::from_dense({}, 0).empty());
  EXPECT_TRUE(LightRows::from_dense({}, 3).empty());
  LightRows built;
  const float zero[3] = {0.0f, 0.0f, 0.0f};
  built.add(0, zero);  // an all-zero entry is left out, the row still counts
  built.end_row();
  EXPECT_EQ(built.rows(), 1u);
  EXPECT_TRUE(built.row(0).empty());
}

}  // namespace test_light_rows
}  // namespace walk::model
