#pragma once
// Frame-rate governor (after Funkhouser & Sequin 1993, per cell rather than per object): keeps a running
// cost estimate per cell and refinement level from measured frame times, and picks the best level whose
// estimate fits the frame budget. Pure CPU; times come from the caller, so it is tested without a clock.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>

namespace walk::render {

// Cheapest first. Reduced: Simplified drawn at half resolution and scaled up, the last resort; Simplified:
// flat polygon light with each cluster at its coarsest level of detail whose error projects under
// kSimplifiedErrorPixels; Coarse: flat polygon light, every triangle of the coarse form; Patches: per vertex.
enum class MovingLevel : std::uint8_t { Reduced = 0, Simplified = 1, Coarse = 2, Patches = 3 };
inline constexpr int kMovingLevels = 4;
// Screen-space error of the simplified levels, in pixels of the full-size frame: about one pixel is where a
// moving silhouette's shift stops being seen; at half resolution two full-size pixels are one drawn.
inline constexpr float kSimplifiedErrorPixels = 1.0f;
inline constexpr float kReducedErrorPixels = 2.0f;
// The screen-space error a moving level allows (0: every triangle of its form).
[[nodiscard]] constexpr float moving_error_pixels(MovingLevel level) {
  return level == MovingLevel::Reduced      ? kReducedErrorPixels
         : level == MovingLevel::Simplified ? kSimplifiedErrorPixels
                                            : 0.0f;
}

class FrameGovernor {
 public:
  explicit FrameGovernor(double target_hz = 60.0);
  [[nodiscard]] double budget_ms() const { return budget_ms_; }
  // A moving frame at `level` in `cell` took `ms` (drawn and finished) and drew `triangles` (negative:
  // not known, and the level's cost model learns nothing).
  void record_moving(std::uint32_t cell, MovingLevel level, double ms, double triangles = -1.0);
  // One accumulation sample took `ms`.
  void record_sample(double ms);
  // The best level whose estimate in this cell fits the budget with 10 % headroom. An untried level is tried
  // unless the level below it is known to leave less than a quarter of the budget. When none fits, the
  // cheapest known level (the higher on a tie): Reduced, the floor, only where it is cheaper.
  // Every `kProbeInterval`-th choice in a cell below the top level tries the next level up once, so an
  // estimate spoilt by one slow frame (a busy CPU) does not hold the cell down for good. A cell with no
  // measurement yet starts at the level of the cell chosen for last (the one just left, of similar cost),
  // not at the top, so walking into a new cell does not cost a slow frame.
  //
  // With `triangles` (what each level would draw in this very frame, from its draw lists), a level is
  // judged by its cost model instead: a line of ms against triangles fitted over every cell's frames at that
  // level (Funkhouser & Sequin's predictive governor), once it has kModelMinFrames frames. A view that turns
  // towards a furnished room is then judged by what it will draw, not by the cell's past frames.
  //
  // `spent_ms`: what this frame has already cost before drawing (the portal walk and the level's draw
  // lists, measured by the caller): the levels are judged against the budget less it. The timed frames
  // the estimates learn from start after it, so it is counted once.
  [[nodiscard]] MovingLevel choose_moving(std::uint32_t cell, std::span<const double> triangles = {},
                                          double spent_ms = 0.0);
  static constexpr int kProbeInterval = 120;
  static constexpr double kModelMinFrames = 8.0;
  // The model's prediction in ms, or a negative number while it has too few frames. The governor judges by
  // the prediction plus kModelSpread times the spread of the model's past misses: it holds a p99, not a
  // mean, and a frame's fill and the shared CPU vary around the line.
  [[nodiscard]] double predict(MovingLevel level, double triangles) const;
  static constexpr double kModelSpread = 2.0;
  // While still: how many accumulation samples fit in one frame (at least 1).
  [[nodiscard]] int samples_per_frame() const;
  // A still frame that draws the view once (full light, its diagonals and sub-quads so far; no accumulation)
  // took `ms` besides making diagonals and sub-quads: the view's own cost, which the next refinement slice
  // leaves time for.
  void record_still_draw(double ms);
  // While still: the CPU time a frame may spend before it draws (a stop's diagonals and sub-quads) and still
  // fit the budget with its drawing: the budget (less its headroom) less the expected draw
  // (expected_still_draw_ms), at most `cap`; `cap` while nothing was measured, and where the drawing leaves
  // less than kMinSliceMs (the frame misses the budget anyway: fewer such frames).
  [[nodiscard]] double still_slice_ms(double cap) const;
  // The larger of the last still frame's draw and an accumulation sample's measured time (a sample draws
  // the view and accumulates it: a margin for what a slice adds to its frame); before either, the
  // full-detail level's mean moving frame (or the last moving frame, if larger or the only one). Negative
  // while nothing was measured.
  [[nodiscard]] double expected_still_draw_ms() const;
  static constexpr double kMinSliceMs = 1.0;  // less than this left: the frame cannot fit
  // Estimate in ms, or a negative number when never measured.
  [[nodiscard]] double estimate(std::uint32_t cell, MovingLevel level) const;

 private:
  double budget_ms_;
  std::unordered_map<std::uint32_t, std::array<double, kMovingLevels>>
      moving_;  // per cell, per level; < 0 unknown
  double sample_ms_ = -1.0;
  double last_moving_ms_ = -1.0;  // the last moving frame's time
  double still_draw_ms_ = -1.0;   // the last still frame's draw
  // Per level: decayed sums for the least-squares line ms = a + b * triangles.
  struct LineFit {
    double n = 0.0, t = 0.0, m = 0.0, tt = 0.0, tm = 0.0;
    double miss_squared = 0.0;  // running mean of (measured - predicted)^2
    void add(double triangles, double ms, double decay);
  };
  std::array<LineFit, kMovingLevels> models_{};
  std::unordered_map<std::uint32_t, int> choices_;  // per cell, since its last probe
  std::optional<std::uint32_t> last_cell_;          // of the last choice
  [[nodiscard]] MovingLevel settled(std::uint32_t cell, std::span<const double> triangles,
                                    double budget_ms) const;
};

}  // namespace walk::render
