#pragma once
// Reading-to-frame latencies in bounded memory: a kiosk runs for months, and keeping every sample (60 a
// second per device) would grow without end. Log-spaced bins, kBinsPerDecade per decade from kLowest to
// kHighest seconds: a few kilobytes per device whatever the run's length, and quantiles within half a bin
// (about 2.3 %) of the exact ones; the count, minimum and maximum are exact.
#include <array>
#include <cstdint>

namespace walk::kiosk {

class LatencyHistogram {
 public:
  static constexpr double kLowest = 1e-6;  // seconds; anything faster lands in the first bin
  static constexpr double kHighest = 1e2;  // seconds; anything slower lands in the last bin
  static constexpr int kBinsPerDecade = 50;
  static constexpr int kBins = 8 * kBinsPerDecade;  // eight decades

  void add(double seconds);
  void merge(const LatencyHistogram& other);
  [[nodiscard]] std::uint64_t count() const { return count_; }
  [[nodiscard]] double min() const { return count_ ? min_ : 0.0; }
  [[nodiscard]] double max() const { return count_ ? max_ : 0.0; }
  // The q-quantile (0..1) in seconds, as the sample of rank q * (count - 1); 0 when empty.
  [[nodiscard]] double quantile(double q) const;

 private:
  std::array<std::uint64_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  double min_ = 0.0, max_ = 0.0;
};

}  // namespace walk::kiosk
