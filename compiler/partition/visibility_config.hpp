#pragma once
// Knobs of the cells stage: the model-space subdivision (Airey's partition priority), the PVS method and
// its sample counts. Read from a scene's [visibility] table (compiler/scene/scene_config.cpp).
#include <cstdint>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "compiler/partition/solid_volumes.hpp"
#include "model/model.hpp"

namespace walk::compiler {

enum class PvsMethod {
  Sampled,       // point sampling with the ray caster: fast, may miss polygons
  Conservative,  // portal flow with separating planes; every polygon of every cell it reaches
  Combined,      // the default: the flow's planes also test each polygon (still conservative: a polygon is
                 // dropped only when no line through the portal sequence can reach its hull), united with
                 // the sampled set (a guard against sight lines through cracks the portals do not model)
};

[[nodiscard]] const char* pvs_method_name(PvsMethod m);
[[nodiscard]] bool parse_pvs_method(const std::string& text, PvsMethod& out);

// The proofs' budget of (viewer piece, target piece) pairs: E1M1 proves about 480,000 pairs a second on 2
// cores (24.4 M in 50.5 s, proofs 16 per item), so 2e9 is about 70 minutes, the same order as the ray
// budgets (kMaxSampledPvsRays, kMaxFirstRoundRays), past which proof_pairs is a typo, not a choice. E1M1
// asks for 3.7e7.
inline constexpr double kMaxProofPairs = 2e9;

struct VisibilityConfig {
  // partition priority = w_occlusion*occlusion + w_balance*balance + w_split*split, each term in 0..1.
  double w_occlusion = 0.5;
  double w_balance = 0.3;
  double w_split = 0.2;
  // A cell is split only by a plane scoring above this. A plane with no wall in it scores at most
  // w_balance + w_split = 0.5, so 0.6 asks for at least a fifth of the cross-section to be wall.
  double threshold = 0.6;
  int max_depth = 16;  // tree depth limit
  // Metres: no cell thinner than this. 0.1 lets a wall's core between its two faces be a cell of its own
  // (off the walk), so that the rooms on either side are cells without the wall in them: on the generated
  // S building the PVS draws 49,164 polygons on average against 102,270 at 0.5 (`walk verify visibility`).
  double min_cell_size = 0.1;
  PvsMethod method = PvsMethod::Combined;
  int sample_points = 32;    // sampled PVS: points per cell (half inside, half on its portals)
  int rays_per_point = 256;  // sampled PVS: directions per point
  // Portal-flow steps per directed portal (testing items along each sequence) before the portal's flow
  // starts again over cells alone and tests items by portal pairs (pvs_flow.hpp).
  std::uint64_t flow_budget = 20'000;
  // Leave out of a cell's PVS every opaque polygon turned away from the whole cell: the renderer culls back
  // faces, so it would never draw them there (EnergyPlus buildings hold every interzone wall twice, back to
  // back, and a room's PVS held both copies of each wall it sees).
  bool cull_back_faces = true;
  // The flow also leaves out what lies wholly behind one convex wall inside a cell, seen from the portal
  // it came through (visibility/occluders.hpp): walls the axial cells cannot follow, such as diagonal ones.
  bool occluders = true;
  // Combined PVS: per polygon the flow lets through and no sample saw, (viewer piece, target piece) pairs
  // the hidden-polygon proof may try (hidden_proof.hpp) before the polygon is kept; 0: no proof. More buy
  // little: on the generated M building 32 pairs keep 804 items a walk cell, 256 keep 795 for 1.55 times
  // the proofs' time.
  int proof_pairs = 32;
  // Pairs the proofs may try over the whole model, checked before they start (compute_cells.cpp). Above it
  // every item's allowance shrinks in proportion, with a warning. Not a scene key: tests lower it.
  double proof_pair_budget = kMaxProofPairs;
  // Structure and detail (vis_items.hpp). A group whose box is shorter than this on its longest side
  // (metres; furniture, fixtures: a 2.64 m conference table is detail, a room's walls are not) is detail,
  // and so is a polygon smaller than detail_area (m^2; trim, mouldings, a curved mesh's facets).
  double detail_extent = 3.0;
  double detail_area = 0.05;
  std::optional<std::regex> structure_groups;  // group names searched: structure whatever their size
  std::optional<std::regex> detail_groups;     // group names searched: detail whatever their size
  // Groups (sorted ids) holding a door or window cut into a wall (the openings stage's): their frames are
  // structure whatever their size. Left as detail, a door's jambs and lintel split no cell, so the door's
  // passage shares a cell with the wall's hollow core beside it and every sight line through the door
  // may creep on through the cores of the walls (on the generated M building, up all ten storeys).
  std::vector<std::uint32_t> frame_groups;
  // Points inside the building (local coordinates) the inside flood starts from (inside_flood.hpp); the
  // compiler gives the scene's start and a point below each luminaire. None: every cell is inside.
  std::vector<model::Vec3> seeds;
  // Solids (local coordinates; the compiler gives the model's, open_regions.hpp): nothing is seen or stands
  // inside them. None: cells are open all through.
  std::vector<SolidVolume> solids;
  // Scene key `solids`: give the cells stage the model's solids (experimental, off by default: on E1M1 it
  // still misses pixels, docs/VISIBILITY.md "Solids").
  bool use_solids = false;
  // The scene file, for errors that name a key of its [visibility] table (set by the compile pipeline).
  std::string source;
  std::string ray_caster = "axial";
  unsigned threads = 0;  // 0: hardware concurrency
  std::uint64_t seed = 1;
};

}  // namespace walk::compiler
