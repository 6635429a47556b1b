// cleanup: stray faces far from the building left out (reported), vertices welded, degenerate faces dropped.
// After the rules, which drop annotation layers (so they do not set the weld tolerance) and install the
// config's materials (the file's own come back here, after them).
#include <spdlog/spdlog.h>

#include "compiler/cleanup/cleanup.hpp"
#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/stages/stages.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

class CleanupStage final : public Stage {
 public:
  const char* name() const override { return "cleanup"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    const auto& config = s.config;
    append_imported_materials(s.model, config, s.imported);
    const std::size_t before = s.model.polygons.size();
    // Before the weld tolerance is taken from the model's size, which one stray face would inflate.
    const StrayStats strays = remove_strays(s.model, config.keep_outliers);
    if (strays.faces > 0)
      spdlog::warn(
          "{}: {} face(s) lie far from the rest of the model, the first at ({:.1f}, {:.1f}, {:.1f}) m "
          "(source line or face {}); {} (set [model] outliers = \"{}\" in {} to change this)",
          config.model_file, strays.faces, strays.first.x, strays.first.y, strays.first.z, strays.first_line,
          config.keep_outliers ? "kept" : "left out", config.keep_outliers ? "drop" : "keep", config.path);
    const CleanupStats c = clean_up(s.model, config.weld_metres);
    s.weld_tolerance = c.weld_tolerance;
    if (c.duplicates_dropped > 0)
      spdlog::warn(
          "{}: {} face(s) repeat another face's corners on the same side and were left out, the first at "
          "source line or face {} (a copy of {}); check the model's export if faces were meant to differ",
          config.model_file, c.duplicates_dropped, c.first_duplicate_line, c.first_duplicated_line);
    if (!has_drawn_faces(s.model))
      throw Error(located(
          config.model_file, 0,
          fmt::format("no face is left to draw after clean-up ({}; {})", strays.summary(), c.summary()),
          "check the model's units and geometry; nothing was written"));
    return StageOutcome::ran(before, s.model.polygons.size(), strays.summary() + "; " + c.summary());
  }
};

}  // namespace

std::unique_ptr<Stage> cleanup_stage() {
  return std::make_unique<CleanupStage>();
}

}  // namespace walk::compiler
