// Progress lines: counts, percentages, ETA and details as shown, safe from many threads, and no control
// characters in the text (the log form goes to journals and CI logs as is).
#include "common/progress.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <thread>
#include <vector>

namespace walk {
namespace progress_test {  // named, not anonymous: the suite compiles as unity batches

class ProgressTest : public ::testing::Test {
 protected:
  void SetUp() override { set_progress_style(ProgressStyle::None); }  // nothing printed while testing lines
};

TEST_F(ProgressTest, ParsesEveryStyleAndRefusesOthers) {
  ProgressStyle s = ProgressStyle::None;
  EXPECT_TRUE(parse_progress_style("bar", s));
  EXPECT_EQ(s, ProgressStyle::Bar);
  EXPECT_TRUE(parse_progress_style("log", s));
  EXPECT_EQ(s, ProgressStyle::Log);
  EXPECT_TRUE(parse_progress_style("none", s));
  EXPECT_EQ(s, ProgressStyle::None);
  EXPECT_TRUE(parse_progress_style("auto", s));
  EXPECT_EQ(s, ProgressStyle::Auto);
  EXPECT_FALSE(parse_progress_style("fancy", s));
  EXPECT_EQ(s, ProgressStyle::Auto);  // unchanged on refusal
}

TEST_F(ProgressTest, CountedWorkShowsShareCountAndUnit) {
  Progress p("cells: hidden proofs", 10, "cells");
  p.advance(4);
  const std::string line = p.line();
  EXPECT_NE(line.find("cells: hidden proofs:"), std::string::npos) << line;
  EXPECT_NE(line.find(" 40%"), std::string::npos) << line;
  EXPECT_NE(line.find("4/10 cells"), std::string::npos) << line;
  EXPECT_NE(line.find("cells/s"), std::string::npos) << line;
}

TEST_F(ProgressTest, UnknownTotalShowsNoShareUntilAFractionIsGiven) {
  Progress p("light", 0, "rounds");
  p.advance(3);
  EXPECT_EQ(p.line().find('%'), std::string::npos) << p.line();
  p.set_fraction(0.25, "unshot 10.00% (stops at 1.00%)");
  const std::string line = p.line();
  EXPECT_NE(line.find(" 25%"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA"), std::string::npos) << line;
  EXPECT_NE(line.find("unshot 10.00% (stops at 1.00%)"), std::string::npos) << line;
}

TEST_F(ProgressTest, FractionsOutsideTheRangeAreClamped) {
  Progress p("light", 0, "rounds");
  p.set_fraction(7.0);
  EXPECT_NE(p.line().find("100%"), std::string::npos) << p.line();
  p.set_fraction(-3.0);
  EXPECT_NE(p.line().find("  0%"), std::string::npos) << p.line();
}

TEST_F(ProgressTest, CountsEveryAdvanceFromManyThreads) {
  Progress p("lod", 8000, "clusters");
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 1000; ++i) p.advance();
    });
  for (auto& t : threads) t.join();
  EXPECT_NE(p.line().find("8000/8000 clusters"), std::string::npos) << p.line();
  EXPECT_NE(p.line().find("100%"), std::string::npos) << p.line();
}

TEST_F(ProgressTest, LinesHoldNoControlCharacters) {
  Progress p("bench render house", 0, "frames");
  p.advance(12);
  p.set_fraction(0.5, "detail");
  for (const char c : p.line()) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << p.line();
}

TEST_F(ProgressTest, AutoIsLogUnderSystemd) {
  ::setenv("INVOCATION_ID", "0123456789abcdef", 1);
  set_progress_style(ProgressStyle::Auto);
  EXPECT_EQ(progress_style(), ProgressStyle::Log);
  ::unsetenv("INVOCATION_ID");
}

}  // namespace progress_test
}  // namespace walk
