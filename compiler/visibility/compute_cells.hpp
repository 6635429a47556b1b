#pragma once
// The cells stage: partition, portals and PVS for a bundle's drawn polygons, written into the bundle as
// CELL (bounds + PVS range), NODE (the splitting-plane tree, O(depth) lookup) and PVSL (polygon ids).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "compiler/partition/portals.hpp"
#include "compiler/partition/visibility_config.hpp"
#include "compiler/visibility/hidden_proof.hpp"
#include "compiler/visibility/inside_flood.hpp"
#include "model/bundle.hpp"

namespace walk::compiler {

struct VisibilityResult {
  // The items the stage worked on (vis_items.hpp): structure polygons, then detail clusters. Every id
  // below (cell polygons, PVS, portal flow) is an item id; item_polygons maps items to bundle polygons.
  std::vector<VisPolygon> polygons;
  std::vector<std::vector<std::uint32_t>> item_polygons;
  std::size_t structure_items = 0;
  std::size_t detail_polygons = 0;
  Partition partition;
  PortalGraph graph;
  std::vector<char>
      inside;  // per cell: some open region of it reached by the inside flood (all, without seeds)
  // With solids (open_regions.hpp): the open regions the flood, samples, flow and proofs ran over.
  std::size_t regions = 0;
  std::uint64_t region_voxels = 0, region_solid_voxels = 0;
  std::size_t region_portals_dropped = 0;
  bool seeded = false;                // the flood had seeds
  std::vector<LeakPath> leaks;        // largest first; without seeds, every open part of the outer boundary
  std::size_t leaks_unconfirmed = 0;  // openings the cell flood reached and the voxel flood did not
  // With solids and seeds: opaque structure items whose front only the void sees (void_facing_items()).
  std::vector<std::uint32_t> void_facing;
  std::vector<std::vector<std::uint32_t>> pvs;  // per cell, sorted item ids, by config.method (empty outside)
  std::vector<std::vector<std::uint32_t>> flow_cells;  // per cell, cells reached by portal flow (not Sampled)
  std::uint64_t flow_steps = 0;
  std::uint32_t flow_fallbacks = 0;       // portals' flows past flow_budget (items by portal pairs)
  std::uint32_t flow_cell_fallbacks = 0;  // ... whose cell-level flow ran past its budget too
  std::uint64_t flow_occluded = 0;        // polygon and portal tests an occluder inside a cell settled
  std::uint64_t sample_rays = 0;
  std::uint64_t back_faces_dropped = 0;  // (cell, polygon) pairs left out by cull_back_faces
  ProofStats proofs;                     // hidden-polygon proofs of the combined PVS
  double proof_pairs_wanted = 0.0;       // the proofs' allowances summed over the items they try
  int proof_pairs_capped = 0;  // pairs an item got when that passed proof_pair_budget; 0: not capped
  double seconds_partition = 0.0, seconds_portals = 0.0, seconds_pvs = 0.0, seconds_proofs = 0.0;
  [[nodiscard]] std::string summary() const;  // one line for the stage record and logs
  // The bundle polygons of `items`, sorted (each polygon is in one item).
  [[nodiscard]] std::vector<std::uint32_t> polygons_of(std::span<const std::uint32_t> items) const;
  // The bundle polygons of a cell's PVS, sorted.
  [[nodiscard]] std::vector<std::uint32_t> polygon_pvs(std::size_t cell) const {
    return polygons_of(pvs[cell]);
  }
};

// Everything from the drawn polygons (local coordinates, as in the bundle). `group_names` (by group index)
// feed the scene's structure and detail patterns. `drawn`: when `polygons` index other triangles than the
// display's (the coarse forms: coarse_forms below), the display's records, whose triangle counts are what
// leaving a polygon out saves; `drawn_indices`, the display's triangles (INDX), which the samples' and
// proofs' ray caster then takes for the structure.
[[nodiscard]] VisibilityResult compute_visibility(std::span<const model::VertexRecord> vertices,
                                                  std::span<const std::uint32_t> indices,
                                                  std::span<const model::PolygonRecord> polygons,
                                                  const VisibilityConfig& config,
                                                  std::span<const std::string> group_names = {},
                                                  std::span<const model::PolygonRecord> drawn = {},
                                                  std::span<const std::uint32_t> drawn_indices = {});

// The polygons over their coarse forms (the fewest triangles over each polygon's outline), which the cells
// stage works on: the same surfaces as the display's diced and light-refined triangles, without the
// triangles the light needed (the medium office refined for light: 317,189 triangles drawn, 388 coarse).
// The display's own where a bundle has no coarse forms.
struct CoarseForms {
  std::vector<model::PolygonRecord> polygons;  // ranges into `indices`
  std::span<const std::uint32_t> indices;      // CIDX, or INDX
};
[[nodiscard]] CoarseForms coarse_forms(std::span<const model::PolygonRecord> polygons,
                                       std::span<const std::uint32_t> indices,
                                       std::span<const model::CoarseRangeRecord> coarse_ranges,
                                       std::span<const std::uint32_t> coarse_indices);

struct CellsStageCounts {
  std::uint64_t polygons_in = 0;
  std::uint64_t cells_out = 0;
  std::string detail;
};

// Fills out.cells, out.nodes and out.pvs from out's vertices, indices and polygons.
CellsStageCounts compute_cells(model::BundleContents& out, const VisibilityConfig& config);

// Rays the sampled PVS may cast in one compile: 2e9, the same bound as the solver's first round (about an
// hour and a half on 2 cores), past which sample_points or rays_per_point is a typo, not a choice.
inline constexpr double kMaxSampledPvsRays = 2e9;
// Throws walk::Error naming the scene file, the keys, the estimate and the limit when `cells` cells would
// cast more; called by compute_cells once the cells are known, before any ray.
void check_sample_budget(const VisibilityConfig& config, std::size_t cells);

}  // namespace walk::compiler
