#include "render/governor.hpp"

#include <algorithm>
#include <cmath>

namespace walk::render {
namespace {

constexpr double kHeadroom = 0.9;   // frame-time jitter on a shared CPU: aim below the budget
constexpr double kSmoothing = 0.3;  // weight of the newest measurement
// Weight kept by the cost model's older frames per new one: about the last 100 frames count.
constexpr double kModelDecay = 0.99;

double blend(double old_ms, double ms) {
  return old_ms < 0.0 ? ms : (1.0 - kSmoothing) * old_ms + kSmoothing * ms;
}

}  // namespace

FrameGovernor::FrameGovernor(double target_hz)
    : budget_ms_(1000.0 / (target_hz > 0.0 && std::isfinite(target_hz) ? target_hz : 60.0)) {}

void FrameGovernor::record_moving(std::uint32_t cell, MovingLevel level, double ms, double triangles) {
  if (!(ms >= 0.0) || !std::isfinite(ms)) return;
  last_moving_ms_ = ms;
  if (triangles >= 0.0 && std::isfinite(triangles)) {
    LineFit& f = models_[std::size_t(level)];
    const double predicted = predict(level, triangles);
    if (predicted >= 0.0) {
      const double miss = ms - predicted;
      f.miss_squared = kModelDecay * f.miss_squared + (1.0 - kModelDecay) * miss * miss;
    }
    f.add(triangles, ms, kModelDecay);
  }
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

void FrameGovernor::LineFit::add(double triangles, double ms, double decay) {
  n = decay * n + 1.0;
  t = decay * t + triangles;
  m = decay * m + ms;
  tt = decay * tt + triangles * triangles;
  tm = decay * tm + triangles * ms;
}

double FrameGovernor::predict(MovingLevel level, double triangles) const {
  const LineFit& f = models_[std::size_t(level)];
  if (f.n < kModelMinFrames || !(triangles >= 0.0)) return -1.0;
  const double mean_t = f.t / f.n, mean_m = f.m / f.n;
  const double var = f.tt / f.n - mean_t * mean_t;
  // Frames that all drew about as much say nothing of the slope: their mean is the prediction.
  const double slope = var > 1e-6 * (mean_t * mean_t + 1.0) ? (f.tm / f.n - mean_t * mean_m) / var : 0.0;
  return std::max(0.0, mean_m + std::max(0.0, slope) * (triangles - mean_t));
}

MovingLevel FrameGovernor::choose_moving(std::uint32_t cell, std::span<const double> triangles,
                                         double spent_ms) {
  const std::uint32_t judged = !moving_.contains(cell) && last_cell_ ? *last_cell_ : cell;
  last_cell_ = cell;
  const double spent = spent_ms > 0.0 && std::isfinite(spent_ms) ? spent_ms : 0.0;
  const MovingLevel level = settled(judged, triangles, budget_ms_ - spent);
  int& count = choices_[cell];
  if (int(level) + 1 < kMovingLevels && ++count >= kProbeInterval) {
    count = 0;
    return MovingLevel(int(level) + 1);
  }
  return level;
}

MovingLevel FrameGovernor::settled(std::uint32_t cell, std::span<const double> triangles,
                                   double budget_ms) const {
  const auto judged = [&](int l) {
    const double p =
        std::size_t(l) < triangles.size() ? predict(MovingLevel(l), triangles[std::size_t(l)]) : -1.0;
    if (p < 0.0) return estimate(cell, MovingLevel(l));
    return p + kModelSpread * std::sqrt(models_[std::size_t(l)].miss_squared);
  };
  for (int l = kMovingLevels - 1; l > 0; --l) {
    const double e = judged(l);
    const double below = judged(l - 1);
    if (e < 0.0) {
      if (below < 0.0 || below <= 0.75 * budget_ms) return MovingLevel(l);
    } else if (e <= kHeadroom * budget_ms) {
      return MovingLevel(l);
    }
  }
  // Nothing fits. Half resolution is the floor only where it is the cheapest: where the frame is not
  // fill-bound (a large model's vertex and draw-call work) it costs what the simplified level costs, and
  // then the better picture is the one to draw. Among known levels the cheapest wins, the higher on a tie.
  const double floor_cost = judged(0);
  if (floor_cost < 0.0) return MovingLevel::Reduced;
  int best = 0;
  for (int l = 1; l < kMovingLevels; ++l) {
    const double e = judged(l);
    if (e >= 0.0 && e <= judged(best)) best = l;
  }
  return MovingLevel(best);
}

int FrameGovernor::samples_per_frame() const {
  if (!(sample_ms_ > 0.0)) return 1;
  return std::clamp(int(kHeadroom * budget_ms_ / sample_ms_), 1, 64);
}

void FrameGovernor::record_still_draw(double ms) {
  if (ms >= 0.0 && std::isfinite(ms)) still_draw_ms_ = ms;
}

double FrameGovernor::expected_still_draw_ms() const {
  // The larger of the two: a slice's own gathering, upload and drawing of the sub-quads it made, and its
  // last unit's overrun, are not in the draw measured before it (on L, slices taken from the view's draw
  // alone made frames of up to 18.7 ms; with a sample's 11.9 ms as the floor, 12.9).
  const double measured = std::max(still_draw_ms_, sample_ms_);
  if (measured >= 0.0) return measured;
  // A still frame draws the full-detail level: its moving frames' mean is the nearest measure, or the last
  // moving frame, which drew no more than a still frame will.
  const LineFit& full = models_[std::size_t(MovingLevel::Patches)];
  if (full.n > 0.0) return std::max(full.m / full.n, last_moving_ms_);
  return last_moving_ms_;
}

double FrameGovernor::still_slice_ms(double cap) const {
  const double draw = expected_still_draw_ms();
  if (!(draw >= 0.0)) return cap;
  const double left = kHeadroom * budget_ms_ - draw;
  // A frame whose drawing alone leaves less than the least slice misses the budget whatever the slice:
  // then the cap, for as few such frames as may be (Sibenik, one cell, took 21 frames of 17-23 ms at the
  // least slice).
  if (left < kMinSliceMs) return cap;
  return std::min(left, cap);
}

}  // namespace walk::render
