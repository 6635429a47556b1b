#pragma once
// One compile stage behind one interface: its name, the hash of its inputs and one run() that reads what
// earlier stages left in the CompileState and writes its own output there. compile_scene (pipeline.cpp)
// runs the list in stages.hpp, times each, logs its stats line and records it in the bundle.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compiler/import/import_model.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/pipeline.hpp"
#include "compiler/radiosity/compact_light.hpp"
#include "compiler/radiosity/patch_set.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// What flows from stage to stage: the model while it is being shaped (import .. luminaires), then the
// bundle's contents and what the mesh stage hands the light stage.
struct CompileState {
  CompileState(const SceneConfig& c, const CompileOptions& o, const model::Bundle* p,
               model::BundleContents& b)
      : config(c), options(o), previous(p), out(b) {}
  const SceneConfig& config;
  const CompileOptions& options;
  const model::Bundle* previous;  // the bundle this compile replaces: a stage may take its output from it

  model::Model model;
  ImportReport imported;
  double weld_tolerance = 0.0;  // metres; clean-up's, which also sets what counts as a vertex on a seam
  std::vector<std::uint32_t> frame_groups;  // the openings stage's (OpeningStats::frame_groups)

  model::BundleContents& out;
  // The mesh stage's, for the light stage.
  std::vector<SurfaceSample> samples;        // one per vertex of a lit polygon
  std::vector<std::uint32_t> sample_vertex;  // bundle vertex of each sample
  // With light refinement, the direct light it gathered at each sample (a row each) for reflectance 1,
  // where sample_refined says it did (seam vertices added after it did not); both empty otherwise.
  SparseLight sample_direct;
  std::vector<std::uint8_t> sample_refined;
  std::vector<Triangle> occluders;                                      // direct lighting's shadow casters
  std::vector<std::pair<std::uint32_t, std::uint32_t>> panel_polygons;  // (bundle polygon, luminaire)
  PatchSet patches;  // vertices numbered as the bundle's, in double precision
  // The patches are the dicing before light refinement: bundle vertices the refinement added are corners
  // of no patch, and take their shot (indirect) light from the patch they lie on.
  bool patches_coarser_than_display = false;
  CompactLight compact;
};

// What a stage did, for its log line and the bundle's stage record.
struct StageOutcome {
  enum class Kind : std::uint8_t { Ran, Skipped, Reused } kind = Kind::Ran;
  std::uint64_t items_in = 0, items_out = 0;
  std::string detail;
  std::optional<double> estimated_error;  // of the light it made, where the stage can tell

  static StageOutcome ran(std::uint64_t in, std::uint64_t out, std::string detail = {}) {
    return {Kind::Ran, in, out, std::move(detail), {}};
  }
  static StageOutcome skipped(std::string why) { return {Kind::Skipped, 0, 0, std::move(why), {}}; }
  static StageOutcome reused(std::string why) { return {Kind::Reused, 0, 0, std::move(why), {}}; }
};

class Stage {
 public:
  virtual ~Stage() = default;
  [[nodiscard]] virtual const char* name() const = 0;
  // Hash of everything the stage's output depends on, recorded in the bundle so the next compile can tell
  // whether it may keep the output; 0: the scene hash stands in (the stage is cheap or its output is not
  // stored whole in the bundle).
  [[nodiscard]] virtual std::uint64_t input_hash(const CompileState&) const { return 0; }
  // Throws walk::Error naming the file, line or key on bad input; writes nothing outside `state`.
  virtual StageOutcome run(CompileState& state, std::uint64_t input_hash) = 0;
};

// The previous bundle's record of stage `name`, if it has one.
[[nodiscard]] const model::StageRecord* previous_record(const CompileState& state, const char* name);

// Whether the model has anything to draw (opaque or glass faces).
[[nodiscard]] bool has_drawn_faces(const model::Model& model);
[[nodiscard]] inline bool drawn(model::Role r) {
  return r == model::Role::Opaque || r == model::Role::Glass;
}

}  // namespace walk::compiler
