#include "render/jitter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace walk::render {

std::vector<JitterSample> jitter_pattern(int count) {
  std::vector<JitterSample> samples;
  if (count <= 0) return samples;
  samples.push_back({0.0f, 0.0f, 1.0f});
  const int n = int(std::ceil(std::sqrt(double(std::max(1, count - 1)))));
  // Cells of an n x n grid in an order that spreads early samples: the bit-reversed (van der Corput) index.
  std::vector<std::pair<std::uint32_t, int>> order;
  for (int i = 0; i < n * n; ++i) {
    std::uint32_t r = std::uint32_t(i);
    r = ((r >> 1) & 0x55555555u) | ((r & 0x55555555u) << 1);
    r = ((r >> 2) & 0x33333333u) | ((r & 0x33333333u) << 2);
    r = ((r >> 4) & 0x0f0f0f0fu) | ((r & 0x0f0f0f0fu) << 4);
    r = ((r >> 8) & 0x00ff00ffu) | ((r & 0x00ff00ffu) << 8);
    r = (r >> 16) | (r << 16);
    order.emplace_back(r, i);
  }
  std::sort(order.begin(), order.end());
  std::uint32_t state = 0x9e3779b9u;  // fixed seed: xorshift32
  auto uniform = [&] {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return float(state >> 8) / float(1u << 24);
  };
  for (int k = 0; int(samples.size()) < count; ++k) {
    const int cell = order[std::size_t(k) % order.size()].second;
    const float dx = -1.0f + 2.0f * (float(cell % n) + uniform()) / float(n);
    const float dy = -1.0f + 2.0f * (float(cell / n) + uniform()) / float(n);
    samples.push_back({dx, dy, (1.0f - std::abs(dx)) * (1.0f - std::abs(dy))});
  }
  return samples;
}

}  // namespace walk::render
