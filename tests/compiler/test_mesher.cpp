// Triangulation of planar polygons with holes: coverage, orientation, grid dicing, degenerate inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "compiler/geometry/coarse_mesh.hpp"
#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/openings.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "test_openings_util.hpp"

namespace walk::compiler {
namespace test_mesher {  // named, not anonymous: the suite compiles as unity batches

using model::Polygon;
using model::Vec3;
using test::area_vector;
using test::polygon_area;

struct MeshCheck {
  double area = 0.0;
  double min_area = 1e300;
  double max_edge = 0.0;
  double open_edge_length = 0.0;  // edges without a twin: the outline, plus any T-junction or gap
  bool finite = true;
  bool all_ccw = true;
};

MeshCheck check(const PolygonMesh& mesh, const Vec3& normal) {
  MeshCheck out;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const std::uint32_t ids[3] = {mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]};
    const Vec3 &a = mesh.vertices.at(ids[0]), &b = mesh.vertices.at(ids[1]), &c = mesh.vertices.at(ids[2]);
    const Vec3 twice = glm::cross(b - a, c - a);
    const double area = 0.5 * glm::length(twice);
    out.area += area;
    out.min_area = std::min(out.min_area, area);
    out.all_ccw = out.all_ccw && glm::dot(twice, normal) > 0.0;
    for (int e = 0; e < 3; ++e) {
      ++edges[{ids[e], ids[(e + 1) % 3]}];
      out.max_edge =
          std::max(out.max_edge, glm::distance(mesh.vertices[ids[e]], mesh.vertices[ids[(e + 1) % 3]]));
    }
  }
  for (const auto& [edge, count] : edges) {
    if (edges.count({edge.second, edge.first}) == 0) {
      out.open_edge_length += glm::distance(mesh.vertices[edge.first], mesh.vertices[edge.second]);
    }
  }
  for (const auto& v : mesh.vertices) out.finite = out.finite && std::isfinite(v.x + v.y + v.z);
  out.finite = out.finite && std::isfinite(mesh.normal.x + mesh.normal.y + mesh.normal.z);
  return out;
}

// The coarse form over the diced vertices: the same surface and orientation in the fewest triangles.
PolygonMesh coarse_over_fine(const PolygonMesh& fine, const std::vector<std::uint32_t>& indices) {
  PolygonMesh out = fine;
  out.triangles = indices;
  return out;
}

double loop_length(const std::vector<Vec3>& loop) {
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) length += glm::distance(loop[i], loop[(i + 1) % loop.size()]);
  return length;
}

double outline_length(const Polygon& p) {
  double length = loop_length(p.vertices);
  for (const auto& hole : p.holes) length += loop_length(hole);
  return length;
}

// An L-shaped room floor with a square column hole, on a tilted plane far from the origin.
Polygon tilted_l_with_hole() {
  const Vec3 origin{1000.0, -2000.0, 50.0};
  const Vec3 u = glm::normalize(Vec3{1.0, 0.2, 0.3});
  const Vec3 v = glm::normalize(glm::cross(glm::normalize(Vec3{0.1, -0.3, 1.0}), u));
  auto at = [&](double x, double y) { return origin + u * x + v * y; };
  Polygon p;
  p.vertices = {at(0, 0), at(6, 0), at(6, 2), at(2.5, 2), at(2.5, 5), at(0, 5)};
  p.holes = {{at(1, 1), at(1, 1.5), at(1.5, 1.5), at(1.5, 1)}};  // clockwise
  return p;
}

TEST(Mesher, NewellNormal) {
  const Vec3 n = polygon_normal({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}});
  EXPECT_NEAR(n.z, 1.0, 1e-12);
  const Vec3 down = polygon_normal({{0, 0, 0}, {0, 1, 0}, {2, 1, 0}, {2, 0, 0}});
  EXPECT_NEAR(down.z, -1.0, 1e-12);
  EXPECT_EQ(polygon_normal({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}), Vec3(0.0));
  EXPECT_EQ(polygon_normal({{0, 0, 0}, {1, 1, 1}}), Vec3(0.0));
}

TEST(Mesher, RectangleIsTwoTriangles) {
  Polygon p;
  p.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 0, 3}, {0, 0, 3}};
  const PolygonMesh mesh = mesh_polygon(p, 0.0);
  EXPECT_EQ(mesh.triangles.size(), 6u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_NEAR(mesh.normal.y, -1.0, 1e-12);
  const MeshCheck c = check(mesh, mesh.normal);
  EXPECT_NEAR(c.area, 12.0, 1e-9);
  EXPECT_TRUE(c.all_ccw);
  for (const auto& v : mesh.vertices) {  // original corners come back bit for bit
    EXPECT_TRUE(std::find(p.vertices.begin(), p.vertices.end(), v) != p.vertices.end());
  }
}

TEST(Mesher, LShapeWithHoleCoversExactly) {
  const Polygon p = tilted_l_with_hole();
  for (double cell : {0.0, 0.5, 0.3}) {
    const PolygonMesh mesh = mesh_polygon(p, cell);
    const MeshCheck c = check(mesh, polygon_normal(p.vertices));
    EXPECT_NEAR(c.area, polygon_area(p), 1e-6 * polygon_area(p)) << cell;
    EXPECT_TRUE(c.all_ccw) << cell;
    EXPECT_TRUE(c.finite);
    EXPECT_GT(c.min_area, 1e-8) << cell;
    // Shared vertices and no T-junctions: only the outline is left without twin edges.
    EXPECT_NEAR(c.open_edge_length, outline_length(p), 1e-6) << cell;
    if (cell > 0.0) {
      EXPECT_LE(c.max_edge, (cell + kMinGridGap) * std::sqrt(2.0)) << cell;
    }
  }
}

TEST(Mesher, GridDicingLimitsEdgeLength) {
  Polygon p;
  p.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 7, 0}, {0, 7, 0}};
  const double cell = 0.5;
  const PolygonMesh mesh = mesh_polygon(p, cell);
  const MeshCheck c = check(mesh, Vec3{0, 0, 1});
  EXPECT_NEAR(c.area, 70.0, 1e-9);
  EXPECT_LE(c.max_edge, cell * std::sqrt(2.0) + 1e-9);
  EXPECT_EQ(mesh.vertices.size(), 21u * 15u);  // a vertex at every grid point
  // Along the boundary, neighbouring vertices are at most one cell apart.
  std::vector<double> bottom;
  for (const auto& v : mesh.vertices) {
    if (v.y == 0.0) bottom.push_back(v.x);
  }
  std::sort(bottom.begin(), bottom.end());
  for (std::size_t i = 1; i < bottom.size(); ++i) EXPECT_LE(bottom[i] - bottom[i - 1], cell + 1e-9);
}

TEST(Mesher, NearlyEqualHeightsMakeNoSlivers) {
  // A bottom corner 0.4 mm below the others would cut a 0.4 mm slab across the whole polygon.
  Polygon p;
  p.vertices = {{0, 0, 0}, {2, -0.0004, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  const PolygonMesh mesh = mesh_polygon(p, 0.0);
  const MeshCheck c = check(mesh, Vec3{0, 0, 1});
  EXPECT_EQ(mesh.triangles.size(), 9u);  // a convex pentagon: 3 triangles
  EXPECT_NEAR(c.area, polygon_area(p), 1e-9);
  EXPECT_GT(c.min_area, 0.5);
}

TEST(Mesher, NotchBelowMergeToleranceStillCorrect) {
  // A reflex corner 0.4 mm up: merging would leave a non-convex slab, so that slab is cut exactly.
  Polygon p;
  p.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {2, 3.0 - 0.0004, 0}, {0, 3, 0}};
  const PolygonMesh mesh = mesh_polygon(p, 0.0);
  const MeshCheck c = check(mesh, Vec3{0, 0, 1});
  EXPECT_NEAR(c.area, polygon_area(p), 1e-9);
  EXPECT_TRUE(c.all_ccw);
  EXPECT_NEAR(c.open_edge_length, outline_length(p), 1e-9);
}

// A wall a fraction of a degree off the y axis, as the house's are, diced: its frame is not the model's,
// so dicing points come back from integer coordinates rounded in a slanted frame. Those on its vertical end
// edges must keep the edges' x and y exactly (a micrometre off, they opened a crack beside the
// perpendicular wall that a sight line through the corner passed).
TEST(Mesher, DicedPointsOnAVerticalEdgeOfASlantedWallStayOnIt) {
  Polygon wall;
  const Vec3 a{-0.75086, -1.47621, -3.2}, b{-1.43080, -1.48455, -3.2};
  wall.vertices = {a, b, {b.x, b.y, -0.2}, {a.x, a.y, -0.2}};
  const PolygonMesh mesh = mesh_polygon(wall, 0.4);
  int on_a = 0, on_b = 0;
  for (const auto& v : mesh.vertices) {
    // Within a micrometre of an end edge in x and y: a dicing point of that edge.
    if (std::abs(v.x - a.x) < 1e-6 && std::abs(v.y - a.y) < 1e-6) {
      ++on_a;
      EXPECT_EQ(v.x, a.x);
      EXPECT_EQ(v.y, a.y);
    }
    if (std::abs(v.x - b.x) < 1e-6 && std::abs(v.y - b.y) < 1e-6) {
      ++on_b;
      EXPECT_EQ(v.x, b.x);
      EXPECT_EQ(v.y, b.y);
    }
  }
  EXPECT_GT(on_a, 2) << "the 3 m edge is cut at 0.4 m steps";
  EXPECT_GT(on_b, 2);
  EXPECT_TRUE(check(mesh, mesh.normal).all_ccw);
  EXPECT_NEAR(check(mesh, mesh.normal).area, 0.5 * glm::length(model::area_vector(wall.vertices)), 1e-9);
}

TEST(Mesher, DegenerateInputsGiveEmptyOrValidMeshes) {
  Polygon zero_area;
  zero_area.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_TRUE(mesh_polygon(zero_area, 0.0).triangles.empty());
  EXPECT_TRUE(mesh_polygon(zero_area, 0.5).triangles.empty());
  EXPECT_TRUE(check(mesh_polygon(zero_area, 0.0), Vec3{0, 0, 1}).finite);

  Polygon two_points;
  two_points.vertices = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_TRUE(mesh_polygon(two_points, 0.0).triangles.empty());
  EXPECT_TRUE(mesh_polygon(Polygon{}, 0.0).triangles.empty());

  Polygon not_a_number;
  not_a_number.vertices = {{0, 0, 0}, {1, 0, 0}, {std::nan(""), 1, 0}};
  const PolygonMesh nan_mesh = mesh_polygon(not_a_number, 0.0);
  EXPECT_TRUE(nan_mesh.triangles.empty());
  EXPECT_TRUE(check(nan_mesh, Vec3{0, 0, 1}).finite);

  Polygon duplicates;
  duplicates.vertices = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
  const MeshCheck d = check(mesh_polygon(duplicates, 0.0), Vec3{0, 0, 1});
  EXPECT_NEAR(d.area, 1.0, 1e-12);
  EXPECT_TRUE(d.all_ccw);

  Polygon touching;  // a hole sharing part of the outer boundary: a notch
  touching.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  touching.holes = {{{1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}}};
  for (double cell : {0.0, 0.7}) {
    const MeshCheck t = check(mesh_polygon(touching, cell), Vec3{0, 0, 1});
    EXPECT_NEAR(t.area, 11.0, 1e-9);
    EXPECT_TRUE(t.all_ccw);
    EXPECT_TRUE(t.finite);
  }

  Polygon covered;  // a hole covering everything
  covered.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  covered.holes = {{{-1, -1, 0}, {-1, 2, 0}, {2, 2, 0}, {2, -1, 0}}};
  EXPECT_TRUE(mesh_polygon(covered, 0.0).triangles.empty());

  Polygon self_touching;  // bow-tie: two triangles meeting at a point
  self_touching.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}};
  const MeshCheck b = check(mesh_polygon(self_touching, 0.0), Vec3{0, 0, 1});
  EXPECT_TRUE(b.finite);
}

TEST(Mesher, WholeHouseAfterCuttingCoversEveryPolygon) {
  model::Model m = read_dxf(std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf");
  for (auto& p : m.polygons) {
    if (p.color == 45 || p.name.find("_HOLE") != std::string::npos) p.role = model::Role::Opening;
    if (p.name.find("_WIN") != std::string::npos) p.role = model::Role::Glass;
  }
  (void)cut_openings(m);
  for (double cell : {0.0, 0.5}) {
    double polygons = 0.0, triangles = 0.0;
    std::size_t count = 0;
    for (const auto& p : m.polygons) {
      const PolygonMesh mesh = mesh_polygon(p, cell);
      const MeshCheck c = check(mesh, polygon_normal(p.vertices));
      EXPECT_TRUE(c.all_ccw) << p.name;
      EXPECT_TRUE(c.finite) << p.name;
      EXPECT_NEAR(c.area, polygon_area(p), 1e-6 * std::max(1.0, polygon_area(p))) << p.name;
      EXPECT_NEAR(c.open_edge_length, outline_length(p), 1e-5) << p.name;
      if (cell > 0.0) {  // every house polygon has its coarse form over its diced vertices
        const auto coarse = coarse_triangles(mesh, mesh_polygon(p, 0.0));
        ASSERT_TRUE(coarse.has_value()) << p.name;
        const MeshCheck cc = check(coarse_over_fine(mesh, *coarse), polygon_normal(p.vertices));
        EXPECT_NEAR(cc.area, polygon_area(p), 1e-6 * std::max(1.0, polygon_area(p))) << p.name;
        EXPECT_TRUE(cc.all_ccw) << p.name;
      }
      polygons += polygon_area(p);
      triangles += c.area;
      count += mesh.triangles.size() / 3;
    }
    EXPECT_NEAR(triangles, polygons, 1e-6 * polygons);
    RecordProperty(cell > 0.0 ? "triangles_cell_0_5" : "triangles_undiced", static_cast<int>(count));
  }
}

TEST(CoarseMesh, SameSurfaceInFewerTrianglesOverTheDicedVertices) {
  Polygon wall;  // 10 m x 3 m with a door notch at the floor and a window hole
  wall.vertices = {{0, 0, 0}, {4, 0, 0},  {4, 0, 2.1}, {5, 0, 2.1},
                   {5, 0, 0}, {10, 0, 0}, {10, 0, 3},  {0, 0, 3}};
  wall.vertices = {wall.vertices.rbegin(), wall.vertices.rend()};  // facing -y: counter-clockwise from there
  wall.holes = {{{7, 0, 1}, {8.5, 0, 1}, {8.5, 0, 2}, {7, 0, 2}}};
  for (const Polygon& p : {tilted_l_with_hole(), wall}) {
    for (double cell : {0.5, 0.25}) {
      const PolygonMesh fine = mesh_polygon(p, cell), coarse = mesh_polygon(p, 0.0);
      const auto indices = coarse_triangles(fine, coarse);
      ASSERT_TRUE(indices.has_value()) << cell;
      EXPECT_EQ(indices->size(), coarse.triangles.size());
      EXPECT_LT(indices->size() * 4, fine.triangles.size()) << cell;
      const MeshCheck c = check(coarse_over_fine(fine, *indices), polygon_normal(p.vertices));
      EXPECT_NEAR(c.area, polygon_area(p), 1e-9 * polygon_area(p)) << cell;
      EXPECT_TRUE(c.all_ccw) << cell;
      EXPECT_NEAR(c.open_edge_length, outline_length(p), 1e-6) << cell;
    }
  }
}

TEST(CoarseMesh, CornerOffTheDicedVerticesFallsBackAndEmptyStaysEmpty) {
  Polygon p;
  p.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  const PolygonMesh coarse = mesh_polygon(p, 0.0);
  PolygonMesh fine = mesh_polygon(p, 1.0);
  // Within the match distance (last-bit differences) a corner still matches ...
  PolygonMesh near = fine;
  for (auto& v : near.vertices)
    if (v == Vec3(4, 3, 0)) v.x += 0.1 * kCoarseVertexMatch;
  EXPECT_TRUE(coarse_triangles(near, coarse).has_value());
  // ... beyond it, there is no diced vertex to draw the coarse corner with.
  for (auto& v : fine.vertices)
    if (v == Vec3(4, 3, 0)) v.x += 10.0 * kCoarseVertexMatch;
  EXPECT_FALSE(coarse_triangles(fine, coarse).has_value());
  const auto empty = coarse_triangles(PolygonMesh{}, mesh_polygon(Polygon{}, 0.0));
  ASSERT_TRUE(empty.has_value());
  EXPECT_TRUE(empty->empty());
}

}  // namespace test_mesher
}  // namespace walk::compiler
