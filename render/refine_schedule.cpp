#include "render/refine_schedule.hpp"

#include <algorithm>

namespace walk::render {

RefineSchedule::RefineSchedule(RefineSettings settings) : settings_(settings) {
  settings_.blend_steps = std::max(0, settings_.blend_steps);
  settings_.aa_samples = std::max(1, settings_.aa_samples);
  settings_.samples_per_frame = std::max(0, settings_.samples_per_frame);
}

void RefineSchedule::view_changed(float moving_patch_weight) {
  stage_ = RefineStage::Moving;
  weight_ = std::clamp(moving_patch_weight, 0.0f, 1.0f);
}

void RefineSchedule::light_changed() {
  if (stage_ == RefineStage::Relit || stage_ == RefineStage::Diagonals ||
      stage_ == RefineStage::Accumulating || stage_ == RefineStage::Idle) {
    // Without diagonals, accumulation's first sample is the plain patch frame already.
    stage_ = settings_.diagonals ? RefineStage::Relit : RefineStage::Accumulating;
    sample_ = 0;
  }
  // Moving or blending: the next frames redraw everything anyway.
}

RefineStep RefineSchedule::next() {
  switch (stage_) {
    case RefineStage::Moving: {
      const RefineStep step{RefineStage::Moving, weight_, -1, false};
      // Blending starts from what was just shown: a moving frame already at patches skips it.
      const int done = int(weight_ * float(settings_.blend_steps) + 0.5f);
      blend_step_ = done;
      stage_ = done >= settings_.blend_steps ? after_blend() : RefineStage::Blending;
      sample_ = 0;
      return step;
    }
    case RefineStage::Blending: {
      ++blend_step_;
      weight_ = std::min(1.0f, float(blend_step_) / float(std::max(1, settings_.blend_steps)));
      if (blend_step_ >= settings_.blend_steps) stage_ = after_blend();
      return {RefineStage::Blending, weight_, -1, false};
    }
    case RefineStage::Relit:
      stage_ = RefineStage::Diagonals;
      return {RefineStage::Relit, 1.0f, -1, false};
    case RefineStage::Diagonals:
      stage_ = RefineStage::Accumulating;
      sample_ = 0;
      return {RefineStage::Diagonals, 1.0f, -1, true};
    case RefineStage::Accumulating: {
      // Sample 0 is the plain (unjittered) patch frame again: the accumulation must hold it too.
      const RefineStep step{RefineStage::Accumulating, 1.0f, sample_, settings_.diagonals};
      weight_ = 1.0f;
      if (++sample_ >= settings_.aa_samples) stage_ = RefineStage::Idle;
      return step;
    }
    case RefineStage::Idle:
      break;
  }
  return {};
}

void RefineSchedule::diagonals_unfinished() {
  if (stage_ == RefineStage::Accumulating && sample_ == 0) stage_ = RefineStage::Diagonals;
}

}  // namespace walk::render
