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
  auto [it, fresh] = moving_.try_emplace(cell, std::array<double, 2>{-1.0, -1.0});
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

MovingLevel FrameGovernor::choose_moving(std::uint32_t cell) const {
  const double fine = estimate(cell, MovingLevel::Patches);
  if (fine >= 0.0) return fine <= kHeadroom * budget_ms_ ? MovingLevel::Patches : MovingLevel::Coarse;
  const double coarse = estimate(cell, MovingLevel::Coarse);
  // Untried patches: try them when coarse is known to leave a quarter of the budget, or nothing is known.
  return coarse < 0.0 || coarse <= 0.75 * budget_ms_ ? MovingLevel::Patches : MovingLevel::Coarse;
}

int FrameGovernor::samples_per_frame() const {
  if (!(sample_ms_ > 0.0)) return 1;
  return std::clamp(int(kHeadroom * budget_ms_ / sample_ms_), 1, 64);
}

}  // namespace walk::render
