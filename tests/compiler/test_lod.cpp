// The lod stage: clusters simplified by meshoptimizer into levels that index the original vertices, with
// errors that grow with the level; flat surfaces lose triangles for free, small clusters and glass are left
// alone, and a bundle gets no sections when nothing was simplified.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include "compiler/lod/simplify_clusters.hpp"
#include "model/model.hpp"

namespace walk::compiler {
namespace test_lod {  // named, not anonymous: the suite compiles as unity batches

// A cluster of n x n unit quads over z = height(x, y), each quad a polygon with vertices of its own (as the
// mesh stage makes them), its coarse form two triangles.
struct Patchwork {
  model::BundleContents b;
  void add_cluster(int n, const std::function<float(float, float)>& height,
                   model::Role role = model::Role::Opaque, float x0 = 0.0f) {
    model::ClusterRecord c{};
    c.polygon_first = std::uint32_t(b.cluster_polygons.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        model::PolygonRecord p{};
        p.first_vertex = std::uint32_t(b.vertices.size());
        p.vertex_count = 4;
        p.role = std::uint32_t(role);
        for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
          model::VertexRecord v{};
          v.position[0] = x0 + float(i + di);
          v.position[1] = float(j + dj);
          v.position[2] = height(v.position[0], v.position[1]);
          v.polygon = std::uint32_t(b.polygons.size());
          b.vertices.push_back(v);
        }
        b.coarse_ranges.push_back({std::uint32_t(b.coarse_indices.size()), 6});
        for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) b.coarse_indices.push_back(p.first_vertex + k);
        b.cluster_polygons.push_back(std::uint32_t(b.polygons.size()));
        b.polygons.push_back(p);
      }
    c.polygon_count = std::uint32_t(n * n);
    b.clusters.push_back(c);
  }
  [[nodiscard]] std::span<const model::LodRangeRecord> levels(std::size_t cluster) const {
    return std::span(b.lod_ranges).subspan(cluster * model::kLodLevels, model::kLodLevels);
  }
  [[nodiscard]] double area(const model::LodRangeRecord& r) const {
    double sum = 0.0;
    for (std::uint32_t i = r.first_index; i < r.first_index + r.index_count; i += 3) {
      const float* a = b.vertices[b.lod_indices[i]].position;
      const float* p = b.vertices[b.lod_indices[i + 1]].position;
      const float* q = b.vertices[b.lod_indices[i + 2]].position;
      const double ux = p[0] - a[0], uy = p[1] - a[1], vx = q[0] - a[0], vy = q[1] - a[1];
      sum += 0.5 * (ux * vy - uy * vx);  // signed: a flipped triangle would subtract
    }
    return sum;
  }
};

TEST(Lod, AFlatClusterLosesTrianglesWithNoErrorAndKeepsItsAreaAndVertices) {
  Patchwork w;
  w.add_cluster(8, [](float, float) { return 0.0f; });  // 128 triangles
  const LodCounts counts = simplify_clusters(w.b, 1);
  EXPECT_EQ(counts.clusters, 1u);
  EXPECT_EQ(counts.simplified, 1u);
  EXPECT_EQ(counts.triangles, 128u);
  ASSERT_EQ(w.b.lod_ranges.size(), model::kLodLevels);
  std::uint32_t previous = 128 * 3;
  for (const auto& r : w.levels(0)) {
    ASSERT_GT(r.index_count, 0u);
    EXPECT_LE(r.index_count, previous / 2 + 3) << "each level about half the one before, or fewer";
    previous = r.index_count;
    EXPECT_LT(r.error, 1e-4f) << "a flat surface simplifies without leaving its plane";
    EXPECT_NEAR(w.area(r), 64.0, 1e-3) << "same surface, same winding";
    for (std::uint32_t i = r.first_index; i < r.first_index + r.index_count; ++i)
      EXPECT_LT(w.b.lod_indices[i], w.b.vertices.size());
  }
}

TEST(Lod, ACurvedClusterHasErrorsThatGrowWithTheLevel) {
  Patchwork w;
  w.add_cluster(16, [](float x, float y) { return 0.5f * std::sin(x * 0.4f) * std::cos(y * 0.4f); });
  (void)simplify_clusters(w.b, 2);
  const auto levels = w.levels(0);
  ASSERT_GT(levels[0].index_count, 0u);
  EXPECT_GT(levels[0].error, 0.0f);
  for (std::size_t l = 1; l < levels.size(); ++l) {
    if (levels[l].index_count == 0) continue;  // as the level before
    EXPECT_LT(levels[l].index_count, levels[l - 1].index_count);
    EXPECT_GE(levels[l].error, levels[l - 1].error);
  }
  // The error is in metres and bounded by the stage's 10 % of the cluster's 16 m extent.
  EXPECT_LE(levels.back().error, 1.7f);
}

TEST(Lod, SmallClustersAndGlassKeepTheirOwnFormAndNothingSimplifiedWritesNoSections) {
  Patchwork w;
  w.add_cluster(3, [](float, float) { return 0.0f; });  // 18 triangles: under kLodMinTriangles
  w.add_cluster(
      8, [](float, float) { return 0.0f; }, model::Role::Glass, 20.0f);
  const LodCounts counts = simplify_clusters(w.b, 1);
  EXPECT_EQ(counts.simplified, 0u);
  EXPECT_TRUE(w.b.lod_ranges.empty());
  EXPECT_TRUE(w.b.lod_indices.empty());
  // With a simplifiable cluster after them, they get empty levels of their own.
  w.add_cluster(
      8, [](float, float) { return 0.0f; }, model::Role::Opaque, 40.0f);
  (void)simplify_clusters(w.b, 1);
  ASSERT_EQ(w.b.lod_ranges.size(), 3 * model::kLodLevels);
  for (std::size_t k : {0u, 1u})
    for (const auto& r : w.levels(k)) EXPECT_EQ(r.index_count, 0u) << "cluster " << k;
  std::set<std::uint32_t> used(w.b.lod_indices.begin(), w.b.lod_indices.end());
  for (std::uint32_t v : used) EXPECT_GE(w.b.vertices[v].position[0], 40.0f) << "only the third cluster's";
}

TEST(Lod, NoCoarseFormMeansNoLevels) {
  Patchwork w;
  w.add_cluster(8, [](float, float) { return 0.0f; });
  w.b.coarse_ranges.clear();
  w.b.coarse_indices.clear();
  EXPECT_EQ(simplify_clusters(w.b, 1).simplified, 0u);
  EXPECT_TRUE(w.b.lod_ranges.empty());
}

}  // namespace test_lod
}  // namespace walk::compiler
