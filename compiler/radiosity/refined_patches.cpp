#include "compiler/radiosity/refined_patches.hpp"

#include <glm/geometric.hpp>
#include <limits>
#include <vector>

#include "common/parallel_for.hpp"
#include "compiler/geometry/triangle_weights.hpp"

namespace walk::compiler {
namespace {

// A point finds its patch by a ray from this far in front of it (metres): above the float rounding of
// bundle vertices, below any gap between surfaces.
constexpr double kLocateOffset = 1e-3;
constexpr std::uint32_t kNoPatch = std::numeric_limits<std::uint32_t>::max();

}  // namespace

PatchLocator::PatchLocator(const PatchSet& patches) : patches_(patches), bvh_(patches.triangles()) {}

std::optional<PatchLocator::Location> PatchLocator::locate(const model::Vec3& point,
                                                           const model::Vec3& normal) const {
  const auto hit = bvh_.closest_facing(point + normal * kLocateOffset, -normal, 0.0, 2.0 * kLocateOffset,
                                       kLocateOffset * 1e-2);
  if (!hit) return std::nullopt;
  const std::uint32_t p = bvh_.triangles()[hit->triangle].polygon;
  const auto& v = patches_.vertices;
  const auto& corners = patches_.patches[p].v;
  return Location{p, triangle_weights(v[corners[0]], v[corners[1]], v[corners[2]],
                                      point + normal * (kLocateOffset - hit->t))};
}

SparseLight patch_area_means(const PatchSet& patches, std::span<const std::uint32_t> display_indices,
                             const SparseLight& per_vertex, const PatchLocator& locator, unsigned threads) {
  const auto& v = patches.vertices;
  const std::size_t count = display_indices.size() / 3;
  std::vector<std::uint32_t> patch_of(count, kNoPatch);
  std::vector<double> area(count, 0.0);
  parallel_ranges(count, 1024, threads, [&](std::size_t first, std::size_t last) {
    for (std::size_t t = first; t < last; ++t) {
      const std::uint32_t a = display_indices[3 * t], b = display_indices[3 * t + 1],
                          c = display_indices[3 * t + 2];
      const model::Vec3 n = glm::cross(v[b] - v[a], v[c] - v[a]);
      const double twice = glm::length(n);
      if (!(twice > 0.0)) continue;
      const auto at = locator.locate((v[a] + v[b] + v[c]) / 3.0, n / twice);
      if (!at) continue;
      patch_of[t] = at->patch;
      area[t] = 0.5 * twice;
    }
  });
  std::vector<double> covered(patches.patches.size(), 0.0);
  for (std::size_t t = 0; t < count; ++t)
    if (patch_of[t] != kNoPatch) covered[patch_of[t]] += area[t];
  SparseLight out(patches.patches.size());
  for (std::size_t t = 0; t < count; ++t) {
    if (patch_of[t] == kNoPatch) continue;
    const double w = area[t] / (3.0 * covered[patch_of[t]]);
    for (int k = 0; k < 3; ++k) out.add(patch_of[t], per_vertex.row(display_indices[3 * t + k]), w);
  }
  for (std::size_t p = 0; p < patches.patches.size(); ++p)
    if (!(covered[p] > 0.0))
      for (const std::uint32_t corner : patches.patches[p].v) out.add(p, per_vertex.row(corner), 1.0 / 3.0);
  return out;
}

}  // namespace walk::compiler
