// Vertices no view sees show their seen neighbours' light (compiler/lighting/hidden_vertices.hpp).
#include <gtest/gtest.h>

#include <vector>

#include "compiler/lighting/hidden_vertices.hpp"

namespace walk::compiler {
namespace test_hidden_vertices {  // named, not anonymous: the suite compiles as unity batches

SparseLight rows(const std::vector<double>& per_vertex) {
  SparseLight light(per_vertex.size());
  for (std::size_t v = 0; v < per_vertex.size(); ++v) {
    double* rgb = light.at(v, 0);
    rgb[0] = rgb[1] = rgb[2] = per_vertex[v];
  }
  return light;
}

TEST(HiddenVertices, AHiddenVertexShowsItsSeenNeighboursAndNothingElseChanges) {
  // A strip across a panel's outline: vertices 0 and 1 behind the panel (hidden, dark), 2 and 3 outside
  // (seen, lit 4 and 6), 4 on another polygon sharing no triangle with them; 5 has no sample (a panel's).
  const std::vector<std::uint32_t> indices{0, 1, 2, 1, 3, 2, 4, 5, 4};
  const std::vector<std::uint32_t> sample_vertex{0, 1, 2, 3, 4};
  const std::vector<std::uint8_t> hidden{1, 1, 0, 0, 1};
  SparseLight light = rows({0.1, 0.2, 4.0, 6.0, 0.3, 9.0});
  EXPECT_EQ(show_hidden_as_neighbours(indices, sample_vertex, hidden, light), 2u);
  EXPECT_DOUBLE_EQ(light.scalar(0), 4.0) << "its one seen neighbour";
  EXPECT_DOUBLE_EQ(light.scalar(1), (4.0 + 6.0 + 4.0) / 3.0) << "2 shared by two triangles counts twice";
  EXPECT_DOUBLE_EQ(light.scalar(2), 4.0);
  EXPECT_DOUBLE_EQ(light.scalar(3), 6.0);
  EXPECT_DOUBLE_EQ(light.scalar(4), 0.3) << "hidden with no seen neighbour: kept";
  EXPECT_DOUBLE_EQ(light.scalar(5), 9.0) << "no sample: kept";
}

TEST(HiddenVertices, NothingHiddenChangesNothing) {
  const std::vector<std::uint32_t> indices{0, 1, 2};
  SparseLight light = rows({1.0, 2.0, 3.0});
  EXPECT_EQ(show_hidden_as_neighbours(indices, std::vector<std::uint32_t>{0, 1, 2},
                                      std::vector<std::uint8_t>{0, 0, 0}, light),
            0u);
  EXPECT_DOUBLE_EQ(light.scalar(0), 1.0);
  EXPECT_EQ(show_hidden_as_neighbours(indices, {}, {}, light), 0u) << "no samples at all";
}

}  // namespace test_hidden_vertices
}  // namespace walk::compiler
