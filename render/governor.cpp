#include "render/governor.hpp"

#include <algorithm>
#include <cmath>

namespace walk::render {
namespace {

constexpr double kHeadroom = 0.9;   // frame-time jitter on a shared CPU: aim below the budget
constexpr double kSmoothing = 0.3;  // weight of the newest measurement

double blend(double old_ms, double ms) {
  return old_ms < 0.0 ? ms : (1.0 - kSmoothing) * old_ms + kSmoothing * ms;
}

}  // namespace

FrameGovernor::FrameGovernor(double target_hz)
    : budget_ms_(1000.0 / (target_hz > 0.0 && std::isfinite(target_hz) ? target_hz : 60.0)) {}

void FrameGovernor::record_moving(std::uint32_t cell, MovingLevel level, double ms) {
  if (!(ms >= 0.0) || !std::isfinite(ms)) return;
  std::array<double, kMovingLevels> unknown;
  unknown.fill(-1.0);
  auto [it, fresh] = moving_.try_emplace(cell, unknown);
  double& slot = it->second[std::size_t(level)];
  slot = blend(slot, ms);
}

void FrameGovernor::record_sample(double ms) {
  if (ms >= 0.0 && std::isfinite(ms)) sample_ms_ = blend(sample_ms_, ms);
}

double FrameGovernor::estimate(std::uint32_t cell, MovingLevel level) const {
  const auto it = moving_.find(cell);
  return it == moving_.end() ? -1.0 : it->second[std::size_t(level)];
}

MovingLevel FrameGovernor::choose_moving(std::uint32_t cell) {
  const std::uint32_t judged = !moving_.contains(cell) && last_cell_ ? *last_cell_ : cell;
  last_cell_ = cell;
  const MovingLevel level = settled(judged);
  int& count = choices_[cell];
  if (int(level) + 1 < kMovingLevels && ++count >= kProbeInterval) {
    count = 0;
    return MovingLevel(int(level) + 1);
  }
  return level;
}

MovingLevel FrameGovernor::settled(std::uint32_t cell) const {
  for (int l = kMovingLevels - 1; l > 0; --l) {
    const double e = estimate(cell, MovingLevel(l));
    const double below = estimate(cell, MovingLevel(l - 1));
    if (e < 0.0) {
      if (below < 0.0 || below <= 0.75 * budget_ms_) return MovingLevel(l);
    } else if (e <= kHeadroom * budget_ms_) {
      return MovingLevel(l);
    }
  }
  return MovingLevel::Reduced;
}

int FrameGovernor::samples_per_frame() const {
  if (!(sample_ms_ > 0.0)) return 1;
  return std::clamp(int(kHeadroom * budget_ms_ / sample_ms_), 1, 64);
}

}  // namespace walk::render
