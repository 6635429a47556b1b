// Clean-up: welding relative to model size, collinear and repeated corners, zero-area faces, non-planar
// faces split, coplanar overlaps detected, and concave faces with holes meshed exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>

#include "compiler/cleanup/cleanup.hpp"
#include "compiler/geometry/mesher.hpp"

namespace walk::compiler {
namespace test_cleanup {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

model::Polygon poly(std::vector<Vec3> v) {
  model::Polygon p;
  p.vertices = std::move(v);
  return p;
}

TEST(Cleanup, DropsExactRepeatsOnTheSameSideOnly) {
  // The Cornell box's OBJ lists each box's "bottom" face as a repeat of another face: the copy would
  // z-fight and take half the light the solver deposits there.
  model::Model m;
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.polygons.push_back(poly(quad));
  m.polygons.back().source_line = 10;
  m.polygons.push_back(poly({quad[2], quad[3], quad[0], quad[1]}));  // the same face from another corner
  m.polygons.back().source_line = 20;
  m.polygons.push_back(poly({quad[3], quad[2], quad[1], quad[0]}));  // the other side: a back-to-back face
  m.polygons.push_back(poly(quad));                                  // the same outline with a hole
  m.polygons.back().holes.push_back({{0.25, 0.25, 0}, {0.25, 0.75, 0}, {0.75, 0.75, 0}, {0.75, 0.25, 0}});
  m.polygons.push_back(poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));  // a part of it: an overlap, not a repeat
  const CleanupStats s = clean_up(m);
  EXPECT_EQ(s.duplicates_dropped, 1u);
  EXPECT_EQ(s.first_duplicate_line, 20u);
  EXPECT_EQ(s.first_duplicated_line, 10u);
  ASSERT_EQ(m.polygons.size(), 4u);
  EXPECT_EQ(m.polygons[0].source_line, 10u);
  EXPECT_NE(s.summary().find("duplicates dropped 1"), std::string::npos) << s.summary();
}

TEST(Cleanup, WeldsCornersWithinToleranceRelativeToModelSize) {
  model::Model m;
  // A 100 m model: weld distance 1e-7 * diagonal ~ 14 um. Corners 5 um apart merge, 1 mm apart do not.
  m.polygons.push_back(poly({{0, 0, 0}, {100, 0, 0}, {100, 100, 0}}));
  m.polygons.push_back(poly({{0, 0, 5e-6}, {100, 100, 0}, {0, 100, 1e-3}}));
  model::Model coarse = m;
  coarse.polygons[1].vertices[0].z = 2e-5;  // 20 um: the scene's weld of 30 um (printing noise) merges it
  const CleanupStats s = clean_up(m);
  EXPECT_NEAR(s.weld_tolerance, 1e-7 * std::sqrt(2.0 * 100 * 100 + 1e-6), 1e-12);
  EXPECT_EQ(s.vertices_welded, 1u);
  EXPECT_EQ(m.polygons[1].vertices[0], Vec3(0, 0, 0));
  EXPECT_EQ(m.polygons[1].vertices[2], Vec3(0, 100, 1e-3));
  const CleanupStats given = clean_up(coarse, 3e-5);
  EXPECT_EQ(given.weld_tolerance, 3e-5);
  EXPECT_EQ(given.vertices_welded, 1u);
  EXPECT_EQ(coarse.polygons[1].vertices[0], Vec3(0, 0, 0));
  EXPECT_EQ(coarse.polygons[1].vertices[2], Vec3(0, 100, 1e-3));
}

TEST(Cleanup, RemovesRepeatedAndCollinearCornersAndDropsZeroAreaFaces) {
  model::Model m;
  m.polygons.push_back(poly({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}));
  m.polygons.push_back(poly({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}));  // collinear: no area
  m.polygons.push_back(poly({{5, 5, 5}, {5, 5, 5}, {6, 6, 6}}));
  const CleanupStats s = clean_up(m);
  ASSERT_EQ(m.polygons.size(), 1u);
  EXPECT_EQ(m.polygons[0].vertices.size(), 4u);
  EXPECT_EQ(s.faces_dropped, 2u);
  EXPECT_GE(s.corners_removed, 2u);
}

TEST(Cleanup, SplitsNonPlanarQuadsOnly) {
  model::Model m;
  // The measured Cornell box's red wall is 3.2 mm out of plane over 0.55 m: split. 0.1 mm: kept.
  m.polygons.push_back(poly({{0, 0, 0}, {0.55, 0, 0}, {0.55, 0, 0.55}, {0, 0.0032, 0.55}}));
  m.polygons.push_back(poly({{0, 1, 0}, {0.55, 1, 0}, {0.55, 1, 0.55}, {0, 1.0001, 0.55}}));
  const CleanupStats s = clean_up(m);
  EXPECT_EQ(s.nonplanar_split, 1u);
  EXPECT_EQ(s.triangles_added, 2u);
  EXPECT_EQ(m.polygons.size(), 3u);
  // The split keeps the surface's orientation.
  for (const auto& p : m.polygons) EXPECT_LT(polygon_normal(p.vertices).y, -0.99);
}

TEST(Cleanup, DetectsSameFacingCoplanarOverlapsOnly) {
  model::Model m;
  m.polygons.push_back(poly({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}));
  m.polygons.push_back(poly({{1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0}}));  // overlaps the first
  m.polygons.push_back(poly({{2, 0, 0}, {4, 0, 0}, {4, -2, 0}}));            // touches it along a point only
  m.polygons.push_back(poly({{0, 2, 0}, {2, 2, 0}, {2, 0, 0}, {0, 0, 0}}));  // back to back with the first
  const CleanupStats s = clean_up(m);
  EXPECT_EQ(s.coplanar_overlaps, 1u);
  EXPECT_EQ(m.polygons.size(), 4u);  // reported, not removed
}

TEST(Cleanup, ConcaveFaceWithHoleMeshesToItsExactArea) {
  // An L-shaped floor (a 4 x 1 foot and a 1 x 3 leg: 7 m2) with a 0.5 x 0.5 hole in the leg: the mesher's
  // triangles cover exactly the face, all facing up.
  model::Polygon p = poly({{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {1, 1, 0}, {1, 4, 0}, {0, 4, 0}});
  p.holes.push_back({{0.25, 2.25, 0}, {0.75, 2.25, 0}, {0.75, 2.75, 0}, {0.25, 2.75, 0}});
  std::reverse(p.holes[0].begin(), p.holes[0].end());  // clockwise about the normal
  model::Model m;
  m.polygons.push_back(p);
  (void)clean_up(m);
  ASSERT_EQ(m.polygons.size(), 1u);
  ASSERT_EQ(m.polygons[0].holes.size(), 1u);
  const PolygonMesh mesh = mesh_polygon(m.polygons[0], 0.0);
  double area = 0.0;
  for (std::size_t i = 0; i < mesh.triangles.size(); i += 3) {
    const Vec3 n = glm::cross(mesh.vertices[mesh.triangles[i + 1]] - mesh.vertices[mesh.triangles[i]],
                              mesh.vertices[mesh.triangles[i + 2]] - mesh.vertices[mesh.triangles[i]]);
    EXPECT_GT(n.z, 0.0);
    area += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(area, 4 + 3 - 0.25, 1e-9);
}

}  // namespace test_cleanup
}  // namespace walk::compiler
