#pragma once
// The paper's adaptive refinement as a state machine, apart from GL so it can be tested alone. While the view
// moves, each frame is drawn at the level the governor chose (coarse flat polygons or radiosity patches).
// Once still: patches are blended in over `blend_steps` frames, then quad diagonals are chosen by colour,
// then jittered samples are accumulated, then nothing is drawn until something changes.
#include <cstdint>

namespace walk::render {

struct RefineSettings {
  int blend_steps = 50;       // frames from coarse polygons to radiosity patches
  int aa_samples = 16;        // accumulated jittered samples (1: no anti-aliasing)
  int samples_per_frame = 0;  // accumulated per displayed frame; 0: as many as the governor says fit
  bool diagonals = true;      // re-split quads along the diagonal of least colour difference
  // With diagonals: quads whose bilinear twist exceeds this fraction of the exposure (white) are subdivided,
  // at most `subdivision_depth` times (each level quarters the twist). 0 depth: no subdivision.
  float subdivision_error = 0.01f;
  int subdivision_depth = 3;
  // Most CPU time a still frame spends making diagonals and sub-quads before it is drawn, the rest left for
  // the next frames: about half the 16.7 ms frame budget, less where the frame's measured drawing (the
  // larger of the view's still draw and a sample) leaves less (FrameGovernor::still_slice_ms). 0: all in
  // one frame (tests that count frames).
  double diagonal_slice_ms = 8.0;
};

// Relit: the view is still and the dimmers moved; the new mix as a plain patch frame (the bundle's
// diagonals, nothing subdivided), since choosing diagonals and subdividing cost the CPU a multiple of a
// frame (S: 54 ms) and a dimmer being turned changes the mix every frame. Diagonals follow once it rests.
enum class RefineStage : std::uint8_t { Moving, Blending, Relit, Diagonals, Accumulating, Idle };

struct RefineStep {
  RefineStage stage = RefineStage::Idle;
  float patch_weight = 1.0f;  // 0: flat polygon light, 1: per-vertex patches
  int sample = -1;            // accumulation sample index, -1 when not accumulating
  bool diagonals = false;     // draw with the colour-chosen diagonals (chosen first at stage Diagonals)
  [[nodiscard]] bool draws() const { return stage != RefineStage::Idle; }
};

class RefineSchedule {
 public:
  explicit RefineSchedule(RefineSettings settings = {});
  // The view moved (or the frame size changed): the next frame is a moving frame at `moving_patch_weight`.
  void view_changed(float moving_patch_weight);
  // Dimmers changed with the view still: patches stay (no coarse flash); with diagonals on, one Relit frame
  // shows the new mix, then diagonals are chosen again for it, and accumulation starts again.
  void light_changed();
  // The step for this frame; advances the schedule.
  [[nodiscard]] RefineStep next();
  // Called after a Diagonals step that did not finish every unit in its time slice: the next step is
  // Diagonals again, and accumulation waits for the last (its samples must all show the same geometry).
  void diagonals_unfinished();
  [[nodiscard]] const RefineSettings& settings() const { return settings_; }
  [[nodiscard]] RefineStage stage() const { return stage_; }

 private:
  [[nodiscard]] RefineStage after_blend() const {
    return settings_.diagonals ? RefineStage::Diagonals : RefineStage::Accumulating;
  }
  RefineSettings settings_;
  RefineStage stage_ = RefineStage::Moving;
  float weight_ = 0.0f;  // patch weight last shown
  int blend_step_ = 0;
  int sample_ = 0;
};

}  // namespace walk::render
