#pragma once
// Inside and outside, as qbsp's outside fill does it but from the inside: a flood from seed points (the
// scene's start, a point below each luminaire) through the open portals a person could pass (not glazed
// ones: glass closes the envelope; not slits narrower than kFloodMinWidth). Cells it reaches are inside,
// where a viewer may walk; the rest only the outside reaches and are dropped from the walk. A leak is an
// opening of the model's outer boundary that the flood reaches, reported with a path of points from a seed to
// it (qbsp's .pts line).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "compiler/partition/portals.hpp"

namespace walk::compiler {

// The flood passes only portals at least this wide both ways (metres): where a person can walk. The gap
// where an interior wall meets an outer one opens into the walls' hollow core, not out of the building.
inline constexpr double kFloodMinWidth = 0.3;

struct LeakPath {
  std::vector<model::Vec3> points;  // from a seed through portal centres to the opening (local coordinates)
  double area = 0.0;                // of the opening, m^2
};

struct InsideFlood {
  std::vector<char> inside;  // per cell; all inside when there are no seeds
  std::vector<LeakPath> leaks;
  std::size_t seeds = 0;
  std::size_t unconfirmed = 0;  // openings the flood reached that `confirm` turned down
};

// Breadth first from the cells in `queue` (already marked in `reached`, per cell) through the portals
// `passes` lets through, marking each cell it reaches and telling `entered` (when set) the cell, the portal
// and the cell it came from. The inside flood and the outside one (void_facing_items) differ only in
// where they start and which portals they pass.
void flood_portals(
    const PortalGraph& graph, std::vector<char>& reached, std::vector<std::uint32_t> queue,
    const std::function<bool(const Portal&)>& passes,
    const std::function<void(std::uint32_t cell, std::uint32_t portal, std::uint32_t from)>& entered = {});

// `locate_seed` gives a seed's cell (kOutside: none, a seed inside a solid); by default the partition's
// node tree. `over_regions` (cells are open regions, open_regions.hpp, where no cell holds a wall's core):
// the flood passes no one-way portal (a face a wall covers on one side), and afterwards the regions sight
// passes into from the walk through any portal (a niche too narrow to walk into) are inside too; leak
// paths are those of the flood itself. `confirm` (when set) has the last word on each opening the flood
// reaches: the voxel flood (voxel_flood.hpp) where cells cannot follow slanted walls.
[[nodiscard]] InsideFlood flood_inside(
    const Partition& partition, const PortalGraph& graph, std::span<const model::Vec3> seeds,
    const std::function<std::uint32_t(const model::Vec3&)>& locate_seed = {}, bool over_regions = false,
    const std::function<bool(const Leak&)>& confirm = {});

}  // namespace walk::compiler
