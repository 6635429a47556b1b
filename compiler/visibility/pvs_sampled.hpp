#pragma once
// Point-sampled PVS (the paper's fast class): rays from random points in each cell and on its portals
// (aimed out through them) in random directions; every polygon a ray meets is visible. It never adds a
// polygon that cannot be seen, but it may miss small or distant ones.
#include <cstdint>
#include <functional>
#include <vector>

#include "compiler/partition/portals.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

struct SampledPvsOptions {
  int points = 32;  // per cell: half inside the cell, half on its portals
  int rays_per_point = 256;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool cull_back_faces = false;  // sight lines pass polygons met from behind (the renderer culls them)
  std::vector<char> cells;       // per cell, 0: leave it out (an outside cell); empty: every cell
  // Where a viewer may stand in a cell (an open region's voxels); empty: anywhere in its box. Points in the
  // cell are drawn up to kSampleTries times until one is usable, else that point is skipped.
  std::function<bool(std::size_t cell, const model::Vec3& p)> usable;
};
inline constexpr int kSampleTries = 16;

[[nodiscard]] std::vector<std::vector<std::uint32_t>> sampled_pvs(
    const Partition& partition, const PortalGraph& graph, const std::vector<VisPolygon>& polygons,
    const RayCaster& caster, const SampledPvsOptions& options, std::uint64_t* rays = nullptr);

// A uniformly random point in a convex winding (fan triangles weighted by area); its first point when
// degenerate.
template <class Rng>
[[nodiscard]] model::Vec3 random_point_in(const Winding& w, Rng& rng);

}  // namespace walk::compiler
