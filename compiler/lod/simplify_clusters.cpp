#include "compiler/lod/simplify_clusters.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <vector>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "model/model.hpp"

namespace walk::compiler {
namespace {

// Each level aims at this fraction of the cluster's triangles (1/2, 1/4, 1/8).
constexpr double kLevelRatio = 0.5;
// A level that keeps more than this fraction of the level before is not worth its own range: stop there.
constexpr double kMinLevelGain = 0.85;
// The most a level may stray, relative to the cluster's extent (meshoptimizer's scale): a 2 m cluster's
// coarsest level stays within 0.2 m, and the renderer draws it only where that projects under its budget.
constexpr float kMaxRelativeError = 0.1f;

struct ClusterLevels {
  std::array<std::vector<std::uint32_t>, model::kLodLevels> indices;  // VERT ids
  std::array<float, model::kLodLevels> error{};
  std::uint64_t triangles = 0;
};

bool simplifiable(const model::PolygonRecord& p) {
  const auto role = static_cast<model::Role>(p.role);
  return role != model::Role::Glass && role != model::Role::Opening && role != model::Role::Ignored;
}

ClusterLevels simplify_one(const model::BundleContents& b, const model::ClusterRecord& cluster) {
  ClusterLevels levels;
  const auto& source = b.coarse_indices;
  std::vector<std::uint32_t> original;  // the cluster's triangles, VERT ids
  for (std::uint32_t i = cluster.polygon_first; i < cluster.polygon_first + cluster.polygon_count; ++i) {
    const std::uint32_t p = b.cluster_polygons[i];
    if (!simplifiable(b.polygons[p])) continue;
    const std::uint32_t first = b.coarse_ranges[p].first_index;
    const std::uint32_t count = b.coarse_ranges[p].index_count;
    original.insert(original.end(), source.begin() + first, source.begin() + first + count);
  }
  levels.triangles = original.size() / 3;
  if (levels.triangles < kLodMinTriangles) return levels;

  // Weld by position: each polygon has vertices of its own, and the simplifier needs shared ones to see
  // the surface. Local ids first (the cluster's vertices only), then meshoptimizer's remap by position.
  std::vector<std::uint32_t> vertex_of;  // local -> VERT id
  std::vector<float> positions;
  std::vector<std::uint32_t> local(original.size());
  {
    std::vector<std::uint32_t> sorted = original;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    vertex_of = sorted;
    for (const std::uint32_t v : sorted)
      positions.insert(positions.end(), b.vertices[v].position, b.vertices[v].position + 3);
    for (std::size_t i = 0; i < original.size(); ++i)
      local[i] = std::uint32_t(std::lower_bound(sorted.begin(), sorted.end(), original[i]) - sorted.begin());
  }
  std::vector<std::uint32_t> remap(vertex_of.size());
  const std::size_t welded_count = meshopt_generateVertexRemap(
      remap.data(), nullptr, vertex_of.size(), positions.data(), vertex_of.size(), 3 * sizeof(float));
  std::vector<float> welded_positions(welded_count * 3);
  std::vector<std::uint32_t> representative(welded_count);  // welded id -> one VERT id at that position
  for (std::size_t v = 0; v < vertex_of.size(); ++v) {
    std::copy_n(&positions[v * 3], 3, &welded_positions[remap[v] * 3]);
    representative[remap[v]] = vertex_of[v];
  }
  std::vector<std::uint32_t> welded(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) welded[i] = remap[local[i]];

  const float scale = meshopt_simplifyScale(welded_positions.data(), welded_count, 3 * sizeof(float));
  std::vector<std::uint32_t> result(welded.size());
  std::size_t previous = welded.size();
  double target = double(welded.size());
  for (std::uint32_t l = 0; l < model::kLodLevels; ++l) {
    target *= kLevelRatio;
    float error = 0.0f;
    // Borders free: locked, the generated building S kept half its triangles at the coarsest level (most
    // detail meshes are open boxes, all border). A crack between two clusters of one object is at most the
    // levels' error, which the renderer keeps under about a pixel.
    const std::size_t n =
        meshopt_simplify(result.data(), welded.data(), welded.size(), welded_positions.data(), welded_count,
                         3 * sizeof(float), std::size_t(target) / 3 * 3, kMaxRelativeError, 0, &error);
    if (n == 0 || double(n) > kMinLevelGain * double(previous)) break;
    previous = n;
    auto& out = levels.indices[l];
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = representative[result[i]];
    levels.error[l] = error * scale;
  }
  return levels;
}

}  // namespace

LodCounts simplify_clusters(model::BundleContents& out, unsigned threads) {
  LodCounts counts;
  out.lod_indices.clear();
  out.lod_ranges.clear();
  // Levels are of the coarse form, the one drawn while moving.
  if (out.clusters.empty() || out.coarse_ranges.size() != out.polygons.size()) return counts;
  std::vector<ClusterLevels> levels(out.clusters.size());
  Progress progress("lod", out.clusters.size(), "clusters");
  parallel_for(out.clusters.size(), threads, [&](std::size_t k) {
    levels[k] = simplify_one(out, out.clusters[k]);
    progress.advance();
  });
  counts.clusters = out.clusters.size();
  out.lod_ranges.reserve(out.clusters.size() * model::kLodLevels);
  for (const auto& c : levels) {
    counts.triangles += c.triangles;
    counts.simplified += !c.indices[0].empty();
    std::uint64_t drawn = c.triangles;
    for (std::uint32_t l = 0; l < model::kLodLevels; ++l) {
      const auto& idx = c.indices[l];
      out.lod_ranges.push_back({std::uint32_t(out.lod_indices.size()), std::uint32_t(idx.size()),
                                idx.empty() ? 0.0f : c.error[l], 0});
      out.lod_indices.insert(out.lod_indices.end(), idx.begin(), idx.end());
      if (!idx.empty()) drawn = idx.size() / 3;
      counts.level_triangles[l] += drawn;
    }
  }
  if (counts.simplified == 0) {  // nothing to gain: no sections at all
    out.lod_indices.clear();
    out.lod_ranges.clear();
  }
  return counts;
}

}  // namespace walk::compiler
