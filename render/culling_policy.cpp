#include "render/culling_policy.hpp"

#include <algorithm>

namespace walk::render {

void CullingPolicy::record(std::uint32_t cell, std::uint64_t hidden, std::uint64_t drawn) {
  if (cell >= cells_.size()) return;
  Cell& c = cells_[cell];
  c.hidden += hidden;
  c.total += hidden + drawn;
  if (++c.probes < kProbeFrames) return;
  if (double(c.hidden) < kMinHiddenShare * double(c.total)) c.resting = kRestFrames;
  c.hidden = c.total = 0;
  c.probes = 0;
}

void CullingPolicy::rested(std::uint32_t cell) {
  if (cell < cells_.size() && cells_[cell].resting > 0) --cells_[cell].resting;
}

std::size_t CullingPolicy::cells_resting() const {
  return std::size_t(
      std::count_if(cells_.begin(), cells_.end(), [](const Cell& c) { return c.resting > 0; }));
}

}  // namespace walk::render
