#pragma once
// Sub-pixel sample positions and filter weights for accumulated anti-aliasing (the paper's last refinement
// step). Pure CPU and deterministic, so a still view always converges to the same picture.
#include <vector>

namespace walk::render {

struct JitterSample {
  float dx = 0.0f;  // offset in pixels, -1..1
  float dy = 0.0f;
  float weight = 1.0f;  // tent filter of radius one pixel: (1 - |dx|)(1 - |dy|)
};

// `count` samples: the first is the pixel centre (so one sample is the plain frame), the rest jittered inside
// the cells of a stratified grid over -1..1 and visited in a scrambled order, so any prefix covers the filter
// support evenly. A tent of radius one pixel overlaps the neighbours, which smooths edges more than a box.
[[nodiscard]] std::vector<JitterSample> jitter_pattern(int count);

}  // namespace walk::render
