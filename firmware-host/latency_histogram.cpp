#include "firmware-host/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace walk::kiosk {
namespace {

int bin_of(double seconds) {
  if (!(seconds > LatencyHistogram::kLowest)) return 0;  // also NaN and negatives: the fastest bin
  const double position = std::log10(seconds / LatencyHistogram::kLowest) * LatencyHistogram::kBinsPerDecade;
  return std::min(LatencyHistogram::kBins - 1, static_cast<int>(position));
}

// Geometric middle of a bin: the best single value for a sample known only to lie in it.
double middle_of(int bin) {
  return LatencyHistogram::kLowest * std::pow(10.0, (bin + 0.5) / LatencyHistogram::kBinsPerDecade);
}

}  // namespace

void LatencyHistogram::add(double seconds) {
  ++bins_[std::size_t(bin_of(seconds))];
  min_ = count_ ? std::min(min_, seconds) : seconds;
  max_ = count_ ? std::max(max_, seconds) : seconds;
  ++count_;
}

void LatencyHistogram::merge(const LatencyHistogram& other) {
  if (!other.count_) return;
  for (std::size_t i = 0; i < bins_.size(); ++i) bins_[i] += other.bins_[i];
  min_ = count_ ? std::min(min_, other.min_) : other.min_;
  max_ = count_ ? std::max(max_, other.max_) : other.max_;
  count_ += other.count_;
}

double LatencyHistogram::quantile(double q) const {
  if (!count_) return 0.0;
  const auto rank = static_cast<std::uint64_t>(std::clamp(q, 0.0, 1.0) * double(count_ - 1));
  std::uint64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += bins_[std::size_t(b)];
    if (seen > rank) return std::clamp(middle_of(b), min_, max_);
  }
  return max_;
}

}  // namespace walk::kiosk
