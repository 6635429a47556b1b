#pragma once
// The lod stage: levels of detail of each cluster for moving frames (the paper's coarse model, per cluster).
// A cluster's opaque triangles of the coarse form (CIDX) are welded by position and simplified with
// meshoptimizer to about 1/2, 1/4 and 1/8 of their count, each level with its geometric error in metres, so
// the renderer can pick per cluster the coarsest level whose error projects under a pixel budget. Levels
// index the original vertices, so their light still mixes live under the dimmers.
#include <array>
#include <cstdint>

#include "model/bundle.hpp"

namespace walk::compiler {

struct LodCounts {
  std::uint64_t clusters = 0;    // clusters looked at
  std::uint64_t simplified = 0;  // clusters with at least one level
  std::uint64_t triangles = 0;   // opaque triangles of the clusters' own form
  std::array<std::uint64_t, model::kLodLevels> level_triangles{};  // drawn at each level (a missing level
                                                                   // counts as the one before)
};

// Clusters with fewer triangles than this keep their own form: a level would save less than its draw range.
inline constexpr std::uint32_t kLodMinTriangles = 32;

// Fills out.lod_indices and out.lod_ranges from out.clusters (nothing when the bundle has no clusters or no
// coarse form).
// `threads` 0: the shared TBB arena.
LodCounts simplify_clusters(model::BundleContents& out, unsigned threads);

}  // namespace walk::compiler
