// cells: the building's shell partitioned into cells by Airey's partition priority, the outside found by a
// flood from inside and dropped, portals found, and a potentially visible set per cell computed per cluster.
#include "compiler/stages/stages.hpp"
#include "compiler/visibility/compute_cells.hpp"

namespace walk::compiler {
namespace {

// Inside-flood seeds: the start at eye height, and a point in the room below each luminaire.
constexpr double kSeedEyeHeight = 1.2;        // metres above the start point, which is on a floor
constexpr double kSeedBelowLuminaire = 0.25;  // metres along the luminaire's normal, into its room

class CellsStage final : public Stage {
 public:
  const char* name() const override { return "cells"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    VisibilityConfig vis = s.config.visibility;
    if (vis.threads == 0) vis.threads = s.options.threads;
    vis.source = s.config.path;
    if (s.config.start)
      vis.seeds.push_back(s.config.start->position - s.model.origin + model::Vec3(0.0, 0.0, kSeedEyeHeight));
    for (const auto& l : s.out.luminaires)
      vis.seeds.push_back(model::Vec3(l.position[0], l.position[1], l.position[2]) +
                          kSeedBelowLuminaire * model::Vec3(l.normal[0], l.normal[1], l.normal[2]));
    if (vis.use_solids) vis.solids = solid_volumes(s.model.solids);
    vis.frame_groups = s.frame_groups;
    const auto counts = compute_cells(s.out, vis);
    return StageOutcome::ran(counts.polygons_in, counts.cells_out, counts.detail);
  }
};

}  // namespace

std::unique_ptr<Stage> cells_stage() {
  return std::make_unique<CellsStage>();
}

}  // namespace walk::compiler
