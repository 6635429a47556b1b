#pragma once
// Conservative PVS by portal flow (Teller & Sequin 1991 as done in Quake's vis): from each portal of a cell,
// walk portal sequences, clipping each next portal by the separating planes of the source portal and the
// last portal passed; a cell is reached when some sequence survives to it. Each polygon of a reached cell is
// then tested against the same planes, which makes the set tight per polygon, not just per cell. With
// `occluders`, polygons and portals wholly in the umbra of one convex wall inside their cell, seen from the
// last portal passed, are left out too (occluders.hpp). As in Quake's vis, each directed portal has a flow
// of its own (a cell sees itself and what its portals see), and portals are flowed fewest might-see cells
// first: a sequence passing a portal whose flow is finished goes on only towards the cells that flow
// reached, which prunes far more than the might-see set. A flow past its step budget falls back to a flow
// over cells only, which stops where no new cell can be reached, and tests items by portal pairs.
#include <cstdint>
#include <vector>

#include "compiler/partition/portals.hpp"
#include "compiler/visibility/occluders.hpp"

namespace walk::compiler {

struct FlowPvs {
  std::vector<std::vector<std::uint32_t>> cells;     // per cell: cells reached (sorted, itself included)
  std::vector<std::vector<std::uint32_t>> polygons;  // per cell: polygons passing the plane test (sorted)
  std::uint64_t steps = 0;                           // recursion steps in all
  std::uint32_t fallbacks = 0;       // portals whose flow ran past the budget (cells by flow, items by pairs)
  std::uint32_t cell_fallbacks = 0;  // ... whose cell-level flow did too (all cells they might see)
  std::uint64_t occluded = 0;        // polygon and portal tests an occluder settled
};

struct FlowOptions {
  std::uint64_t budget = 2'000'000;
  unsigned threads = 0;
  bool occluders = true;        // single-occluder culling inside cells
  bool cull_back_faces = true;  // occluders block only sight lines meeting their front
  std::vector<char> sources;    // per cell, 0: no flow from it (an outside cell); empty: every cell
};

[[nodiscard]] FlowPvs portal_flow_pvs(const Partition& partition, const PortalGraph& graph,
                                      const std::vector<VisPolygon>& polygons, const FlowOptions& options);

}  // namespace walk::compiler
