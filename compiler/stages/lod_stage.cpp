// lod: simplified levels of each large cluster (meshoptimizer) for the kiosk's moving frames.
#include <string>

#include "compiler/lod/simplify_clusters.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

class LodStage final : public Stage {
 public:
  const char* name() const override { return "lod"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    const LodCounts lod = simplify_clusters(s.out, s.options.threads);
    if (lod.simplified == 0)
      return StageOutcome::skipped("no cluster of " + std::to_string(kLodMinTriangles) +
                                   " triangles or more to simplify");
    return StageOutcome::ran(
        lod.triangles, lod.level_triangles.back(),
        std::to_string(lod.simplified) + " of " + std::to_string(lod.clusters) + " clusters; " +
            std::to_string(lod.triangles) + " triangles -> " + std::to_string(lod.level_triangles[0]) + ", " +
            std::to_string(lod.level_triangles[1]) + ", " + std::to_string(lod.level_triangles[2]));
  }
};

}  // namespace

std::unique_ptr<Stage> lod_stage() {
  return std::make_unique<LodStage>();
}

}  // namespace walk::compiler
