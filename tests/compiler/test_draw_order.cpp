// Index-buffer layout for the cells: every polygon keeps its triangles, and each cell's PVS becomes fewer
// contiguous ranges (the renderer's multi-draw entries).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "compiler/visibility/draw_order.hpp"
#include "model/model.hpp"

namespace walk::compiler {
namespace test_draw_order {  // named, not anonymous: the suite compiles as unity batches

// Six one-triangle polygons (polygon 3 is glass) and three cells seeing {0,2,4}, {2,4,5} and {1,3}.
model::BundleContents six_polygons_three_cells() {
  model::BundleContents b;
  for (std::uint32_t p = 0; p < 6; ++p) {
    model::PolygonRecord rec{};
    rec.first_index = 3 * p;
    rec.index_count = 3;
    rec.role = static_cast<std::uint32_t>(p == 3 ? model::Role::Glass : model::Role::Opaque);
    b.polygons.push_back(rec);
    for (std::uint32_t k = 0; k < 3; ++k) b.indices.push_back(10 * p + k);
    b.coarse_ranges.push_back({3 * p, 3});
    for (std::uint32_t k = 0; k < 3; ++k) b.coarse_indices.push_back(10 * p + k);
  }
  b.pvs = {0, 2, 4, 2, 4, 5, 1, 3};
  b.cells.push_back({{}, {}, 0, 3});
  b.cells.push_back({{}, {}, 3, 3});
  b.cells.push_back({{}, {}, 6, 2});
  return b;
}

TEST(DrawOrder, CellsBecomeContiguousAndPolygonsKeepTheirTriangles) {
  model::BundleContents b = six_polygons_three_cells();
  const model::BundleContents before = b;
  // Id order: cell 0 is three runs (0, 2, 4), cell 1 two (2 and 4-5), cell 2 one opaque and one glass.
  EXPECT_EQ(count_draw_ranges(b), 7u);
  const DrawOrderCounts counts = order_for_cells(b);
  EXPECT_EQ(counts.ranges_before, 7u);
  // Membership (cells 0, 1, 2) 100, 001, 110, -, 110, 010 has Gray ranks 111, 001, 100, -, 100, 011, so the
  // order is 0, 2, 4, 5, 1, then glass 3: cells 0 (0-2-4) and 1 (2-4-5) are one run each, cell 2 one opaque
  // and one glass. (Plain sorting of the membership gives 5: 2, 4, 0, 5, 1 splits cell 1.)
  EXPECT_EQ(counts.ranges_after, 4u);
  EXPECT_EQ(count_draw_ranges(b), 4u);
  for (std::size_t p = 0; p < b.polygons.size(); ++p) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      EXPECT_EQ(b.indices[b.polygons[p].first_index + k], before.indices[before.polygons[p].first_index + k]);
      EXPECT_EQ(b.coarse_indices[b.coarse_ranges[p].first_index + k], 10 * p + k);
    }
  }
  EXPECT_EQ(b.polygons[3].first_index, 15u) << "glass is laid out after everything opaque";
}

TEST(DrawOrder, NoCellsOrEmptyPvsChangesNothingThatMatters) {
  model::BundleContents b = six_polygons_three_cells();
  b.cells.clear();
  b.pvs.clear();
  const DrawOrderCounts counts = order_for_cells(b);
  EXPECT_EQ(counts.ranges_before, 0u);
  EXPECT_EQ(counts.ranges_after, 0u);
  for (std::size_t p = 0; p < 6; ++p)
    EXPECT_EQ(b.indices[b.polygons[p].first_index], 10 * p) << "every polygon still has its triangle";
  model::BundleContents empty;
  EXPECT_EQ(order_for_cells(empty).ranges_after, 0u);
}

// The same cells seeing clusters: polygons 0 and 2 one cluster, the rest alone (a cluster's polygons share
// its membership), and in a second form with polygon 4 in two clusters (membership then made per polygon).
// Both lay the polygons out exactly as the polygon-level PVS they expand to.
TEST(DrawOrder, ClustersLayOutAsThePolygonsTheyHold) {
  const auto with_clusters = [](const std::vector<std::vector<std::uint32_t>>& clusters,
                                const std::vector<std::vector<std::uint32_t>>& cell_clusters) {
    model::BundleContents b = six_polygons_three_cells();
    model::BundleContents expanded = b;
    b.pvs.clear();
    expanded.pvs.clear();
    for (const auto& k : clusters) {
      model::ClusterRecord rec{};
      rec.polygon_first = std::uint32_t(b.cluster_polygons.size());
      rec.polygon_count = std::uint32_t(k.size());
      b.cluster_polygons.insert(b.cluster_polygons.end(), k.begin(), k.end());
      b.clusters.push_back(rec);
    }
    for (std::size_t c = 0; c < cell_clusters.size(); ++c) {
      std::vector<std::uint32_t> polygons;
      for (const auto k : cell_clusters[c])
        polygons.insert(polygons.end(), clusters[k].begin(), clusters[k].end());
      std::sort(polygons.begin(), polygons.end());
      polygons.erase(std::unique(polygons.begin(), polygons.end()), polygons.end());
      b.cells[c] = {{}, {}, std::uint32_t(b.pvs.size()), std::uint32_t(cell_clusters[c].size())};
      b.pvs.insert(b.pvs.end(), cell_clusters[c].begin(), cell_clusters[c].end());
      expanded.cells[c] = {{}, {}, std::uint32_t(expanded.pvs.size()), std::uint32_t(polygons.size())};
      expanded.pvs.insert(expanded.pvs.end(), polygons.begin(), polygons.end());
    }
    EXPECT_EQ(count_draw_ranges(b, 2), count_draw_ranges(expanded, 1));
    const DrawOrderCounts counts = order_for_cells(b, 2), expected = order_for_cells(expanded, 1);
    EXPECT_EQ(counts.ranges_before, expected.ranges_before);
    EXPECT_EQ(counts.ranges_after, expected.ranges_after);
    EXPECT_EQ(b.indices, expanded.indices);
    EXPECT_EQ(b.coarse_indices, expanded.coarse_indices);
    for (std::size_t p = 0; p < b.polygons.size(); ++p)
      EXPECT_EQ(b.polygons[p].first_index, expanded.polygons[p].first_index) << p;
    return counts;
  };
  // Clusters {0, 2}, {4}, {5}, {1}, {3}: cells see {0,2,4}, {2,4,5} (whole clusters: {0,2} stands for 2)
  // and {1,3}. Polygon 0 now shares cluster {0, 2}'s membership.
  const DrawOrderCounts one = with_clusters({{0, 2}, {4}, {5}, {1}, {3}}, {{0, 1}, {0, 1, 2}, {3, 4}});
  EXPECT_GT(one.ranges_before, one.ranges_after);
  // Polygon 4 in two clusters.
  (void)with_clusters({{0, 2}, {4}, {4, 5}, {1}, {3}}, {{0, 1}, {2}, {3, 4}});
}

}  // namespace test_draw_order
}  // namespace walk::compiler
