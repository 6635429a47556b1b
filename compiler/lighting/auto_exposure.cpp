#include "compiler/lighting/auto_exposure.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace walk::compiler {

double weighted_percentile(std::span<const double> values, std::span<const double> weights, double share) {
  const std::size_t n = std::min(values.size(), weights.size());
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) total += std::max(0.0, weights[i]);
  if (!(total > 0.0)) return 0.0;
  const double wanted = std::clamp(share, 0.0, 1.0) * total;
  double running = 0.0;
  for (const std::size_t i : order) {
    const double w = std::max(0.0, weights[i]);
    if (w <= 0.0) continue;
    running += w;
    if (running >= wanted) return values[i];
  }
  // Round-off left the sum a hair short: the largest weighted value.
  for (auto it = order.rbegin(); it != order.rend(); ++it)
    if (weights[*it] > 0.0) return values[*it];
  return 0.0;
}

}  // namespace walk::compiler
