// import: the scene's model file (DXF, 2D plan, Quake .map, OBJ/glTF through assimp) -> polygons.
#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class ImportStage final : public Stage {
 public:
  const char* name() const override { return "import"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    s.model = import_model(s.config, &s.imported);
    check_coordinates(s.model, s.config.model_file);  // non-finite or absurd: an error naming file and line
    return StageOutcome::ran(0, s.model.polygons.size(), s.imported.format + ": " + s.imported.detail);
  }
};

}  // namespace

std::unique_ptr<Stage> import_stage() {
  return std::make_unique<ImportStage>();
}

}  // namespace walk::compiler
