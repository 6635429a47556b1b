#include "compiler/scene/work_budget.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <glm/geometric.hpp>

#include "model/error.hpp"

namespace walk::compiler {

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
}

double estimated_patches(const model::Model& model, double grid) {
  double patches = 0.0;
  for (const auto& p : model.polygons) {
    if (p.role != model::Role::Opaque && p.role != model::Role::Glass) continue;
    double area = 0.5 * glm::length(model::area_vector(p.vertices));
    for (const auto& hole : p.holes) area -= 0.5 * glm::length(model::area_vector(hole));
    patches += grid > 0.0 ? std::max(1.0, area / (grid * grid)) : 1.0;
  }
  return patches;
}

void check_patch_budget(const model::Model& model, const SceneConfig& config, std::uint64_t memory_bytes) {
  if (memory_bytes == 0) return;  // the machine would not say: nothing to bound by
  const double patches = estimated_patches(model, config.lighting.grid);
  const double bytes =
      patches * (kBytesPerPatch +
                 kBytesPerPatchCircuit * std::min(kCircuitsReachingAPatch,
                                                  double(std::max<std::size_t>(1, model.circuits.size()))));
  const double limit = kMemoryShare * double(memory_bytes);
  if (bytes > limit)
    throw Error(located(
        config.path, 0,
        fmt::format("[lighting] grid = {} m would make about {:.3g} patches needing about {:.1f} GiB, above "
                    "the {:.1f} GiB this machine allows a compile ({:.0f} % of its memory)",
                    config.lighting.grid, patches, bytes / double(1ull << 30), limit / double(1ull << 30),
                    100.0 * kMemoryShare),
        fmt::format("raise grid to at least {:.3g} m, or compile on a machine with more memory",
                    config.lighting.grid * std::sqrt(bytes / limit) * 1.05)));
}

void check_ray_budget(const model::Model& model, const SceneConfig& config) {
  // With a target the light stage chooses the rays itself, within kMaxFirstRoundRays.
  if (config.lighting.method != LightingMethod::Radiosity || config.lighting.target_error) return;
  double watts = 0.0;
  for (const auto& l : model.luminaires) watts += (l.power.r + l.power.g + l.power.b) / 3.0;
  const double rays = config.lighting.rays_per_watt * watts;
  if (rays > kMaxFirstRoundRays)
    throw Error(located(
        config.path, 0,
        fmt::format(
            "[lighting] rays_per_watt = {:g} with {:.1f} W of luminaires would cast about {:.3g} rays "
            "in the first round alone, above the limit of {:.0e}",
            config.lighting.rays_per_watt, watts, rays, kMaxFirstRoundRays),
        fmt::format("lower rays_per_watt to at most {:.3g}", kMaxFirstRoundRays / watts)));
}

}  // namespace walk::compiler
