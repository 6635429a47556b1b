// Latency histograms: quantiles within half a bin of the exact ones, exact count and extremes, merging equal
// to adding, and memory that does not grow with the number of samples (a kiosk runs for months).
#include "firmware-host/latency_histogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace walk::kiosk {
namespace latency_histogram_test {  // named, not anonymous: the suite compiles as unity batches

// Half a bin of 50 per decade: 10^(0.5/50) - 1.
constexpr double kHalfBin = 0.0233;

TEST(LatencyHistogram, QuantilesMatchTheExactOnesWithinHalfABin) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> latency(std::log(0.005), 0.6);  // about 5 ms, a long tail
  LatencyHistogram h;
  std::vector<double> exact;
  for (int i = 0; i < 20000; ++i) {
    const double s = latency(rng);
    h.add(s);
    exact.push_back(s);
  }
  std::sort(exact.begin(), exact.end());
  for (const double q : {0.0, 0.1, 0.5, 0.9, 0.99, 0.999, 1.0}) {
    const double truth = exact[static_cast<std::size_t>(q * double(exact.size() - 1))];
    EXPECT_NEAR(h.quantile(q) / truth, 1.0, kHalfBin) << "q " << q;
  }
  EXPECT_EQ(h.count(), exact.size());
  EXPECT_EQ(h.min(), exact.front());
  EXPECT_EQ(h.max(), exact.back());
}

TEST(LatencyHistogram, MergingEqualsAddingAndTheSizeIsFixed) {
  LatencyHistogram a, b, both;
  for (int i = 1; i <= 1000; ++i) {
    (i % 3 ? a : b).add(i * 1e-4);
    both.add(i * 1e-4);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), both.count());
  EXPECT_EQ(a.max(), both.max());
  EXPECT_EQ(a.min(), both.min());
  for (const double q : {0.25, 0.5, 0.99}) EXPECT_EQ(a.quantile(q), both.quantile(q));
  static_assert(sizeof(LatencyHistogram) < 4096, "bounded: a few kilobytes whatever the run's length");
}

TEST(LatencyHistogram, EmptyOutOfRangeAndGarbageSamplesStayBounded) {
  LatencyHistogram h;
  EXPECT_EQ(h.quantile(0.5), 0.0);
  EXPECT_EQ(h.max(), 0.0);
  h.add(1e-9);  // below the lowest bin
  h.add(1e6);   // above the highest
  h.add(-1.0);  // a clock that stepped back
  h.add(std::nan(""));
  EXPECT_EQ(h.count(), 4u);
  EXPECT_TRUE(std::isfinite(h.quantile(0.5)));
  EXPECT_LE(h.quantile(1.0), 1e6);
}

}  // namespace latency_histogram_test
}  // namespace walk::kiosk
