// Light crossing between the solver's patches and the refined display triangles on them.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "compiler/radiosity/refined_patches.hpp"

namespace walk::compiler {
namespace test_refined_patches {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Patch 0: the triangle (0,0,0) (2,0,0) (0,2,0) facing +z, refined into four by its edges' midpoints 3, 4,
// 5. Patch 1: the same triangle facing -z (a wall drawn from both rooms, back to back), corners 6, 7, 8,
// not refined. Patch 2 beside them, on which no display triangle lies.
struct Refined {
  PatchSet set;
  std::vector<std::uint32_t> display;
  Refined() {
    set.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                    {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
    EXPECT_TRUE(set.add(0, 1, 2, model::Rgb(0.5), 0));
    EXPECT_TRUE(set.add(6, 8, 7, model::Rgb(0.5), 1));
    EXPECT_TRUE(set.add(9, 10, 11, model::Rgb(0.5), 2));
    display = {0, 3, 5, 3, 1, 4, 5, 4, 2, 3, 4, 5,  // patch 0's four pieces
               6, 8, 7,                             // patch 1 whole
               0, 0, 1};                            // a degenerate one: skipped
  }
};

SparseLight one_circuit(const std::vector<double>& per_vertex) {
  SparseLight light(per_vertex.size());
  for (std::size_t v = 0; v < per_vertex.size(); ++v)
    if (per_vertex[v] != 0.0) {
      double* rgb = light.at(v, 0);
      rgb[0] = rgb[1] = rgb[2] = per_vertex[v];
    }
  return light;
}

TEST(RefinedPatches, APointFindsThePatchOnItsOwnSide) {
  const Refined r;
  const PatchLocator locator(r.set);
  const auto front = locator.locate({0.5, 0.5, 0.0}, {0, 0, 1});
  ASSERT_TRUE(front.has_value());
  EXPECT_EQ(front->patch, 0u);
  EXPECT_NEAR(front->weights[0], 0.5, 1e-9);
  EXPECT_NEAR(front->weights[1], 0.25, 1e-9);
  EXPECT_NEAR(front->weights[2], 0.25, 1e-9);
  const auto back = locator.locate({0.5, 0.5, 0.0}, {0, 0, -1});
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->patch, 1u) << "the back-to-back copy facing the other way";
  EXPECT_FALSE(locator.locate({3.0, 3.0, 0.0}, {0, 0, 1}).has_value()) << "off every patch";
  EXPECT_FALSE(locator.locate({0.5, 0.5, 0.01}, {0, 0, 1}).has_value()) << "1 cm in front: not on it";
}

TEST(RefinedPatches, APatchShootsTheAreaMeanOfTheLightOnIt) {
  const Refined r;
  const PatchLocator locator(r.set);
  // Dark corners and one bright midpoint (vertex 3, on the edge 0-1): three of the four equal pieces hold
  // it, each piece's mean a third of it, so the patch's mean is a quarter of it. Its corners alone say 0.
  std::vector<double> light(r.set.vertices.size(), 0.0);
  light[3] = 4.0;
  light[6] = light[7] = light[8] = 2.0;  // the back copy: uniform
  light[9] = 3.0;                        // patch 2: corners 3, 0, 0
  const SparseLight means = patch_area_means(r.set, r.display, one_circuit(light), locator, 2);
  ASSERT_EQ(means.rows(), 3u);
  EXPECT_NEAR(means.scalar(0), 1.0, 1e-12);
  EXPECT_NEAR(means.scalar(1), 2.0, 1e-12) << "the front's bright piece does not leak to the back";
  EXPECT_NEAR(means.scalar(2), 1.0, 1e-12) << "no display triangle on it: its corners' mean";
  // Light linear over the patch: every piece's mean is its centroid's light, and so is the sum.
  std::vector<double> linear(r.set.vertices.size(), 0.0);
  for (std::size_t v = 0; v < 6; ++v) linear[v] = 1.0 + r.set.vertices[v].x + 2.0 * r.set.vertices[v].y;
  const SparseLight flat = patch_area_means(r.set, r.display, one_circuit(linear), locator, 1);
  EXPECT_NEAR(flat.scalar(0), 1.0 + 2.0 / 3.0 + 4.0 / 3.0, 1e-12);
}

}  // namespace test_refined_patches
}  // namespace walk::compiler
