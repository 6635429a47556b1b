// T-junction repair across diced polygons: seams between coplanar polygons become shared chains of identical
// vertices, so rays at a slanted seam cannot pass between float-rounded triangles. Degenerate inputs, area
// and orientation, and the real EnergyPlus house's floors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <set>
#include <string>

#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/openings.hpp"
#include "compiler/geometry/t_junctions.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {
namespace test_t_junctions {  // named, not anonymous: the suite compiles as unity batches

using model::Polygon;
using model::Vec3;

// EnergyPlus scenes weld at 20 um; the repair's tolerance in the pipeline is the weld distance.
constexpr double kTolerance = 2e-5;
// The brute-force check's own test for coplanar meshes (with the plane test on each vertex below): normals
// parallel to a rounding, either facing. The repair groups by kSeamNormalBin instead, a criterion these
// tests' exactly parallel normals meet either way.
constexpr double kParallelCosine = 1.0 - 1e-9;

Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  Polygon p;
  p.vertices = {a, b, c, d};
  return p;
}

// Two floors at z = -0.2 meeting along a seam from (x0, 0) to (x1, 5), like the house's floors along the top
// of a slanted basement wall (2 cm over 3.4 m).
struct Seam {
  Vec3 s0, s1;
};
std::vector<PolygonMesh> floors_along(const Seam& seam, double grid) {
  const double z = seam.s0.z;
  return {mesh_polygon(quad({0, 0, z}, seam.s0, seam.s1, {0, 5, z}), grid),
          mesh_polygon(quad(seam.s0, {8, 0, z}, {8, 5, z}, seam.s1), grid)};
}
const Seam kHouseLikeSeam{{3.4, 0.0, -0.2}, {3.42, 5.0, -0.2}};
std::vector<PolygonMesh> slanted_floors(double grid) {
  return floors_along(kHouseLikeSeam, grid);
}

double area(const PolygonMesh& m) {
  double sum = 0.0;
  for (std::size_t t = 0; t + 2 < m.triangles.size(); t += 3) {
    const Vec3 &a = m.vertices[m.triangles[t]], &b = m.vertices[m.triangles[t + 1]],
               &c = m.vertices[m.triangles[t + 2]];
    sum += 0.5 * glm::dot(glm::cross(b - a, c - a), m.normal);  // signed: a flipped triangle subtracts
  }
  return sum;
}

bool all_counter_clockwise(const PolygonMesh& m) {
  for (std::size_t t = 0; t + 2 < m.triangles.size(); t += 3) {
    const Vec3 &a = m.vertices[m.triangles[t]], &b = m.vertices[m.triangles[t + 1]],
               &c = m.vertices[m.triangles[t + 2]];
    if (!(glm::dot(glm::cross(b - a, c - a), m.normal) > 0.0)) return false;
  }
  return true;
}

// Edges of a mesh's triangles without their reverse in the same mesh: its outline and holes.
std::vector<std::pair<std::uint32_t, std::uint32_t>> outline_edges(const PolygonMesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> all;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3)
    for (int e = 0; e < 3; ++e) all.insert({mesh.triangles[t + e], mesh.triangles[t + (e + 1) % 3]});
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& [a, b] : all)
    if (!all.contains({b, a})) out.push_back({a, b});
  return out;
}

double outline_length(const PolygonMesh& mesh) {
  double sum = 0.0;
  for (const auto& [a, b] : outline_edges(mesh)) sum += glm::distance(mesh.vertices[a], mesh.vertices[b]);
  return sum;
}

// Vertices of one mesh lying inside a slanted outline edge of a coplanar other mesh (open T-junctions), by
// brute force.
std::size_t open_t_junctions(const std::vector<PolygonMesh>& meshes) {
  std::size_t open = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const auto& mesh = meshes[m];
    for (const auto& [ia, ib] : outline_edges(mesh)) {
      const Vec3 a = mesh.vertices[ia], b = mesh.vertices[ib];
      if ((a.x == b.x) + (a.y == b.y) + (a.z == b.z) >= 2) continue;
      const Vec3 d = b - a;
      const double len = glm::length(d);
      for (std::size_t o = 0; o < meshes.size(); ++o) {
        if (o == m || std::abs(glm::dot(meshes[o].normal, mesh.normal)) < kParallelCosine) continue;
        for (const Vec3& x : meshes[o].vertices) {
          const double s = glm::dot(x - a, d) / (len * len);
          if (s * len <= kTolerance || (1 - s) * len <= kTolerance) continue;
          if (std::abs(glm::dot(x - a, mesh.normal)) > kSeamNoise) continue;
          if (glm::distance(x, a + d * s) <= kTolerance) ++open;
        }
      }
    }
  }
  return open;
}

// The meshes as the bundle stores them: float vertices, read back in double.
std::vector<Triangle> as_float_triangles(const std::vector<PolygonMesh>& meshes) {
  std::vector<Triangle> out;
  auto rounded = [](const Vec3& v) { return Vec3(glm::vec3(v)); };
  for (std::uint32_t m = 0; m < meshes.size(); ++m) {
    const auto& mesh = meshes[m];
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3)
      out.push_back({rounded(mesh.vertices[mesh.triangles[t]]), rounded(mesh.vertices[mesh.triangles[t + 1]]),
                     rounded(mesh.vertices[mesh.triangles[t + 2]]), m});
  }
  return out;
}

// Rays from above aimed at points of the seam line: how many pass through the floor.
std::size_t rays_through_seam(const std::vector<PolygonMesh>& meshes, Vec3 s0, Vec3 s1, std::size_t count) {
  const auto caster = make_ray_caster("brute", as_float_triangles(meshes));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0), tilt(-0.5, 0.5);
  std::size_t through = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 target = s0 + (s1 - s0) * unit(rng);
    const Vec3 origin = target + Vec3(tilt(rng), tilt(rng), 1.0);
    if (!caster->occluded({origin, (target - origin) * 2.0, 0.0, 1.0})) ++through;
  }
  return through;
}

// The mesher's vertices come out of Clipper's integer grid (1e-7 m steps in the plane) and are stored in
// float: along a slanted seam each side's vertices stray from the line by up to 3e-7 m, and where the two
// sides stray apart, a ray aimed at the seam passes between them. These seams are ones where that happens
// (found by sweeping offsets and slopes); the house-like one happens to overlap instead.
TEST(TJunctions, SlantedSeamsBetweenDicedFloorsAreClosedInFloat) {
  const std::vector<Seam> seams{kHouseLikeSeam,
                                {{3.4, 0.0, -0.2}, {3.4131, 5.0, -0.2}},
                                {{3.4, 0.0, -0.2}, {4.5, 5.0, -0.2}},
                                {{3.43, 0.0, -0.2}, {3.06, 5.0, -0.2}},
                                {{2.917, 0.0, -0.2}, {2.547, 5.0, -0.2}},
                                {{1.3, 0.0, 2.7}, {0.93, 5.0, 2.7}}};
  std::size_t through_before = 0;
  for (const Seam& seam : seams) {
    std::vector<PolygonMesh> meshes = floors_along(seam, 0.4);
    // Diced apart, each floor's seam vertices lie inside the other's seam edges.
    EXPECT_GT(open_t_junctions(meshes), 10u);
    through_before += rays_through_seam(meshes, seam.s0, seam.s1, 20000);

    const double area0 = area(meshes[0]), area1 = area(meshes[1]);
    const TJunctionStats stats = repair_t_junctions(meshes, kTolerance);
    EXPECT_GT(stats.vertices_inserted, 10u);
    EXPECT_GT(stats.triangles_split, 0u);
    EXPECT_EQ(open_t_junctions(meshes), 0u);
    EXPECT_EQ(rays_through_seam(meshes, seam.s0, seam.s1, 50000), 0u) << seam.s1.x;
    // The same surface (to the vertices' stray from the line), facing the same way: a folded piece would
    // subtract its area and fail the orientation check.
    EXPECT_NEAR(area(meshes[0]), area0, kTolerance * outline_length(meshes[0]));
    EXPECT_NEAR(area(meshes[1]), area1, kTolerance * outline_length(meshes[1]));
    EXPECT_TRUE(all_counter_clockwise(meshes[0]));
    EXPECT_TRUE(all_counter_clockwise(meshes[1]));
    // Running again finds nothing left to do.
    EXPECT_EQ(repair_t_junctions(meshes, kTolerance).vertices_inserted, 0u);
  }
  EXPECT_GT(through_before, 1000u) << "the crack this repair exists for";
}

// Two ceiling strips at 45 degrees meeting along x, as in E1M1 above its slipgate hall: the corners of the
// shared edge agree in y but differ in z by a rounding, as plane intersections in double leave them. Unless
// the mesher places both strips' dicing points on the edge in z as well as y, each strip's points take z
// from its own plane frame (1e-7 m apart) and float rounding opens a crack between the strips, which the
// repair leaves alone because the strips' edges are axial and their points off each other's plane.
// Two ceiling strips at 45 degrees meeting along x, E1M1's polygons 6552 and 6553 as its CSG leaves them:
// the shared edge's corners agree in y but differ in z by a rounding. The mesher must place each strip's
// dicing points on that edge in z as well as y: from the plane frame they came 1.4e-7 m above it in one
// strip and 2.8e-7 m below in the other, float rounding put the two rows a float step apart, and a sight
// line through the slit between them showed E1M1's verify a wall the PVS rightly leaves out. The T-junction
// repair cannot close it: the strips' edges are axial and their points off each other's plane.
TEST(TJunctions, SlopedStripsMeetingAlongAnAxisKeepTheEdgeExactly) {
  const double y = 39.152000000000001, z = 6.8448;
  const Vec3 s0{3.4431999999999992, y, 6.8447999999999976}, s1{10.352000000000004, y, 6.8447999999999984};
  const std::array<Vec3, 4> lower{s0, s1, Vec3{10.758399999999998, 39.558399999999992, 6.4383999999999943},
                                  Vec3{3.4431999999999992, 39.558399999999992, 6.4383999999999943}};
  const std::array<Vec3, 4> upper{Vec3{3.4431999999999992, 38.948799999999991, 7.048},
                                  Vec3{10.148800000000001, 38.948799999999991, 7.048}, s1, s0};
  // Each outline from each of its corners: the plane frame, and so the dicing, follows the first.
  for (int first = 0; first < 4; ++first) {
    const auto from = [&](const std::array<Vec3, 4>& c) {
      return quad(c[first], c[(first + 1) % 4], c[(first + 2) % 4], c[(first + 3) % 4]);
    };
    std::size_t on_edge = 0;
    for (const Polygon& strip : {from(lower), from(upper)})
      for (const Vec3& v : mesh_polygon(strip, 1.0).vertices)
        if (v.y == y) {
          ++on_edge;
          EXPECT_NEAR(v.z, z, 1e-12) << "a dicing point on the shared edge is off it in z, at x " << v.x
                                     << ", outlines from corner " << first;
        }
    EXPECT_GE(on_edge, 14u) << "both strips are diced along the edge";
  }
}

TEST(TJunctions, SplitTrianglesKeepTheirQuadPartnersNextToThem) {
  // A polygon diced into quads (pairs of triangles in a row), its neighbour diced finer along a slanted seam.
  std::vector<PolygonMesh> meshes = slanted_floors(0.4);
  const std::size_t count = meshes[0].triangles.size() / 3;
  auto pairs = [](const PolygonMesh& m, std::size_t n) {
    std::size_t shared = 0;  // consecutive triangles (0,1), (2,3), ... sharing an edge
    for (std::size_t t = 0; t + 1 < n; t += 2) {
      std::size_t common = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) common += m.triangles[3 * t + i] == m.triangles[3 * (t + 1) + j];
      shared += common == 2;
    }
    return shared;
  };
  const std::size_t before = pairs(meshes[0], count);
  repair_t_junctions(meshes, kTolerance);
  EXPECT_EQ(pairs(meshes[0], count), before);
  EXPECT_GT(meshes[0].triangles.size() / 3, count);
}

TEST(TJunctions, WhatIsNotOnTheEdgeStaysOut) {
  const double z = 0.0;
  // A slanted edge from (0,0) to (4,1): mesh A is the triangle below it, mesh B supplies test points.
  auto with_point = [&](const Vec3& x) {
    PolygonMesh a;
    a.vertices = {{0, 0, z}, {4, 0, z}, {4, 1, z}};
    a.triangles = {0, 1, 2};
    PolygonMesh b;  // a sliver triangle whose first corner is the point under test, same plane and facing
    b.vertices = {x, x + Vec3(-1, 3, 0), x + Vec3(-2, 3, 0)};
    b.triangles = {0, 1, 2};
    std::vector<PolygonMesh> meshes{a, b};
    return repair_t_junctions(meshes, kTolerance).vertices_inserted;
  };
  const Vec3 a{0, 0, z}, c{4, 1, z};
  const Vec3 off = glm::normalize(Vec3(-1, 4, 0));                          // in-plane normal of the edge a-c
  EXPECT_EQ(with_point(a + (c - a) * 0.5), 1u);                             // on the edge
  EXPECT_EQ(with_point(a + (c - a) * 0.5 + off * (0.9 * kTolerance)), 1u);  // just off it
  EXPECT_EQ(with_point(a + (c - a) * 0.5 + off * (1.1 * kTolerance)), 0u);  // beyond tolerance
  EXPECT_EQ(with_point(a), 0u);                                             // an end of the edge
  EXPECT_EQ(with_point(a + glm::normalize(c - a) * (0.5 * kTolerance)), 0u);  // within tolerance of an end
  EXPECT_EQ(with_point(a - (c - a) * 0.1), 0u);                               // on the line, before a
  EXPECT_EQ(with_point(c + (c - a) * 0.1), 0u);                               // on the line, past c
  EXPECT_EQ(with_point(a + (c - a) * 0.5 + Vec3(0, 0, 1e-6)), 0u);            // off the plane

  // A neighbour in another plane (a wall standing on the edge, its foot along it: a crease) gives its
  // corners on the edge's line, but not where its foot is off the line by more than double noise, though well
  // within the weld tolerance: across planes only corners both planes put on the line are joined.
  auto wall_at = [&](const Vec3& foot) {
    PolygonMesh floor;
    floor.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}};
    floor.triangles = {0, 1, 2};
    PolygonMesh wall;
    const Vec3 along(1, 0.25, 0), up(0, 0, 3);
    wall.vertices = {foot, foot + along, foot + along + up, foot + up};
    wall.normal = glm::normalize(glm::cross(along, up));
    wall.triangles = {0, 1, 2, 0, 2, 3};
    std::vector<PolygonMesh> corner{floor, wall};
    const TJunctionStats stats = repair_t_junctions(corner, kTolerance);
    EXPECT_EQ(stats.crease_vertices_inserted, stats.vertices_inserted);
    return stats.vertices_inserted;
  };
  EXPECT_EQ(wall_at({2, 0.5, 0}), 2u);
  EXPECT_EQ(wall_at({2, 0.5 + 1e-7, 0}), 0u);
}

// A 45-degree ceiling meeting a wall, as in DM1 (polygons 3451 and 3454): the wall's top corners lie on the
// ceiling's edge along the crease, inside it. Each becomes a vertex of the ceiling's edge, the ceiling keeps
// its area and orientation, and nothing else changes; a wall corner a rounding off the crease stays out.
TEST(TJunctions, CreaseCornersGoIntoTheEdgeAcrossThePlanes) {
  const double c = 0.37;  // the crease: x = 0, z = y + c
  auto meshes_with = [&](double lift) {
    return std::vector<PolygonMesh>{
        mesh_polygon(quad({1, 0, c}, {1, 2, 2 + c}, {0, 2, 2 + c}, {0, 0, c}), 0.0),  // the ceiling
        mesh_polygon(quad({0, 0.5, 0}, {0, 1.5, 0}, {0, 1.5, 1.5 + c + lift}, {0, 0.5, 0.5 + c}), 0.0)};
  };
  std::vector<PolygonMesh> meshes = meshes_with(0.0);
  const double ceiling_area = area(meshes[0]);
  const std::vector<Vec3> wall_vertices = meshes[1].vertices;
  const TJunctionStats stats = repair_t_junctions(meshes, kTolerance);
  EXPECT_EQ(stats.vertices_inserted, 2u);
  EXPECT_EQ(stats.crease_vertices_inserted, 2u);
  EXPECT_EQ(meshes[1].vertices, wall_vertices) << "the ceiling's corners lie beyond the wall's edge";
  std::size_t on_crease = 0;
  for (const auto& [a, b] : outline_edges(meshes[0]))
    for (const Vec3& v : {meshes[0].vertices[a], meshes[0].vertices[b]})
      on_crease += v.x == 0.0 && (v == Vec3(0, 0.5, 0.5 + c) || v == Vec3(0, 1.5, 1.5 + c));
  EXPECT_EQ(on_crease, 4u) << "both wall corners on the ceiling's outline, each ending two edges";
  EXPECT_NEAR(area(meshes[0]), ceiling_area, 1e-12);
  EXPECT_TRUE(all_counter_clockwise(meshes[0]));
  EXPECT_EQ(repair_t_junctions(meshes, kTolerance).vertices_inserted, 0u) << "nothing left to do";

  std::vector<PolygonMesh> off = meshes_with(1e-7);  // one corner 1e-7 m above the crease
  EXPECT_EQ(repair_t_junctions(off, kTolerance).vertices_inserted, 1u);
}

// E1M1's sky over a slanted wall (polygon 1899 on walls 2586 and 2587): the sky is diced, and its dicing
// point on the slanted edge lies off the edge's line by Clipper's rounding (about 3e-7 m), so the diced
// edges' own lines miss the wall's corner on the true line. Grouped by the outline edge they were diced
// from, the wall's corner goes into the diced edge; the sky's dicing point, off the wall's plane, stays out.
TEST(TJunctions, CreaseCornersGoIntoADicedEdge) {
  const double z = 8.064;
  const Vec3 c0{-2.856, -0.8784, z}, c1{-2.2464, 0.1376, z}, corner{-2.49024, -0.2688, z};
  Polygon sky;
  sky.vertices = {{-2.856, 0.1376, z}, c0, c1};  // from the corner off the slanted edge, as E1M1 has it
  const Vec3 up{0, 0, -1.2};
  std::vector<PolygonMesh> meshes{mesh_polygon(sky, 1.0),
                                  mesh_polygon(quad(c0, corner, corner + up, c0 + up), 0.0),
                                  mesh_polygon(quad(corner, c1, c1 + up, corner + up), 0.0)};
  // The case this test is about: a dicing point on the slanted edge, off its line by more than double noise.
  const Vec3 d = glm::normalize(c1 - c0);
  std::size_t off_line = 0;
  for (const Vec3& v : meshes[0].vertices) {
    const Vec3 foot = c0 + d * glm::dot(v - c0, d);
    const double t = glm::dot(v - c0, d) / glm::distance(c0, c1);
    off_line += t > 0.01 && t < 0.99 && glm::distance(v, foot) > kSeamNoise && glm::distance(v, foot) < 1e-6;
  }
  ASSERT_EQ(off_line, 1u);
  const double sky_area = area(meshes[0]);
  const std::vector<Vec3> wall = meshes[2].vertices;
  const TJunctionStats stats = repair_t_junctions(meshes, kTolerance);
  EXPECT_EQ(stats.crease_vertices_inserted, 1u);
  std::size_t corners = 0;
  for (const auto& [a, b] : outline_edges(meshes[0]))
    corners += (meshes[0].vertices[a] == corner) + (meshes[0].vertices[b] == corner);
  EXPECT_EQ(corners, 2u) << "the wall's corner ends two of the sky's outline edges";
  EXPECT_EQ(meshes[2].vertices, wall) << "the sky's dicing point is off the wall's plane";
  // The corner lies on the true line, the diced edge up to the dicing point's rounding off it.
  EXPECT_NEAR(area(meshes[0]), sky_area, kDicingPointNoise * outline_length(meshes[0]));
  EXPECT_TRUE(all_counter_clockwise(meshes[0]));
}

// Coplanar meshes are grouped by normal up to sign: on a wall at 45 degrees two components are equal, and
// normals a rounding apart must still land in one group (choosing the sign by the largest component split
// them).
// An edge along y whose corners' x differ by a rounding (CSG's 1e-15 m) is along an axis, as one with equal
// corners: a neighbour's corner on it is not inserted (float keeps both coordinates for every point on
// it). Its coarse form and its diced form, whose dicing points keep x exactly, then agree. An edge a
// micrometre off the axis is slanted and takes the corner.
TEST(TJunctions, EdgesAlongAnAxisToARoundingAreAxial) {
  auto inserted_with_skew = [&](double skew) {
    PolygonMesh left;  // its right edge from (1, 0) to (1 + skew, 2)
    left.vertices = {{0, 0, 0}, {1, 0, 0}, {1 + skew, 2, 0}, {0, 2, 0}};
    left.triangles = {0, 1, 2, 0, 2, 3};
    PolygonMesh right;  // two squares' corner at the edge's middle
    right.vertices = {{1 + skew / 2, 1, 0}, {3, 1, 0}, {3, 2, 0}, {1 + skew, 2, 0}};
    right.triangles = {0, 1, 2, 0, 2, 3};
    std::vector<PolygonMesh> meshes{left, right};
    return repair_t_junctions(meshes, kTolerance).vertices_inserted;
  };
  EXPECT_EQ(inserted_with_skew(0.0), 0u);
  EXPECT_EQ(inserted_with_skew(1e-15), 0u);
  EXPECT_EQ(inserted_with_skew(0.5 * kAxialNoise), 0u);
  EXPECT_EQ(inserted_with_skew(2.0 * kAxialNoise), 1u);
  EXPECT_EQ(inserted_with_skew(1e-6), 1u);
}

// A point within the weld distance of an edge but beyond the apex of a triangle thinner than that (a sliver
// beside a column cut) would fold a piece over: the triangle stays whole and keeps its T-junction. The same
// point goes into the edge of a triangle that is not that thin.
TEST(TJunctions, ASplitThatWouldFoldATriangleIsRefused) {
  const Vec3 a{0, 0, 0}, b{4, 1, 0};
  const Vec3 inward = glm::normalize(Vec3(-1, 4, 0));  // to the left of a -> b, into the triangle
  const Vec3 x = a + (b - a) * 0.25 + inward * (0.5 * kTolerance);
  auto repaired_with_apex_at = [&](double height) {
    PolygonMesh triangle;
    triangle.vertices = {a, b, (a + b) * 0.5 + inward * height};
    triangle.triangles = {0, 1, 2};
    PolygonMesh other;  // below the edge, with a corner at x
    other.vertices = {x, x + Vec3(1, -3, 0), x + Vec3(2, -3, 0)};
    other.triangles = {0, 1, 2};
    std::vector<PolygonMesh> meshes{triangle, other};
    const TJunctionStats stats = repair_t_junctions(meshes, kTolerance);
    EXPECT_TRUE(all_counter_clockwise(meshes[0]));
    EXPECT_NEAR(area(meshes[0]), area(triangle), kTolerance * outline_length(triangle));
    return std::pair{stats, meshes[0]};
  };
  const auto [thin, kept] = repaired_with_apex_at(1e-6);
  EXPECT_EQ(thin.splits_refused, 1u);
  EXPECT_EQ(thin.vertices_inserted, 0u);
  EXPECT_EQ(kept.triangles.size(), 3u);
  const auto [fat, split] = repaired_with_apex_at(1.0);
  EXPECT_EQ(fat.splits_refused, 0u);
  EXPECT_EQ(fat.vertices_inserted, 1u);
  EXPECT_EQ(split.triangles.size(), 6u);
}

TEST(TJunctions, DiagonalWallNormalsARoundingApartStillMeet) {
  PolygonMesh a;
  a.vertices = {{0, 0, 0}, {2, 2, 0}, {0, 0, 2}};
  a.triangles = {0, 1, 2};
  a.normal = {0.70710678118654757, -0.70710678118654746, 0.0};
  PolygonMesh b;  // across the slanted edge (2,2,0)-(0,0,2), with a corner at its middle
  b.vertices = {{2, 2, 0}, {2, 2, 2}, {0, 0, 2}, {1, 1, 1}};
  b.triangles = {0, 1, 3, 3, 1, 2};
  b.normal = {0.70710678118654746, -0.70710678118654757, 0.0};
  std::vector<PolygonMesh> meshes{a, b};
  EXPECT_EQ(repair_t_junctions(meshes, kTolerance).vertices_inserted, 1u);
  EXPECT_EQ(meshes[0].triangles.size(), 6u);
  EXPECT_TRUE(all_counter_clockwise(meshes[0]));
}

TEST(TJunctions, DegenerateInputsAreLeftAlone) {
  std::vector<PolygonMesh> none;
  EXPECT_EQ(repair_t_junctions(none, kTolerance).vertices_inserted, 0u);
  std::vector<PolygonMesh> empty(3);  // meshes without triangles
  EXPECT_EQ(repair_t_junctions(empty, kTolerance).vertices_inserted, 0u);
  // Zero-length and collinear (zero-area) triangles beside a real one: nothing inserted, nothing lost.
  PolygonMesh flat;
  flat.vertices = {{0, 0, 0}, {0, 0, 0}, {1, 1, 0}, {2, 2, 0}};
  flat.triangles = {0, 1, 2, 0, 2, 3};
  PolygonMesh real;
  real.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}};
  real.triangles = {0, 1, 2};
  std::vector<PolygonMesh> meshes{flat, real};
  const TJunctionStats s = repair_t_junctions(meshes, kTolerance);
  for (const auto& m : meshes)
    for (const Vec3& v : m.vertices) EXPECT_TRUE(std::isfinite(v.x + v.y + v.z));
  // The diagonal (0,0)-(2,2) of `real` holds flat's (1,1): a real T-junction, inserted once, and the
  // triangle stays counter-clockwise with the same area.
  EXPECT_EQ(s.vertices_inserted, 1u);
  EXPECT_NEAR(area(meshes[1]), 2.0, 1e-12);
  EXPECT_TRUE(all_counter_clockwise(meshes[1]));
  // A triangle with a repeated index has no boundary, alone in its mesh or beside another triangle: its
  // corner on `real`'s diagonal goes into no edge.
  for (const std::vector<std::uint32_t>& indices :
       {std::vector<std::uint32_t>{0, 0, 1}, std::vector<std::uint32_t>{0, 1, 1, 2, 3, 4}}) {
    PolygonMesh repeated;
    repeated.vertices = {{1, 1, 0}, {5, 5, 0}, {10, 0, 0}, {11, 0, 0}, {11, 1, 0}};
    repeated.triangles = indices;
    std::vector<PolygonMesh> pair{repeated, real};
    EXPECT_EQ(repair_t_junctions(pair, kTolerance).vertices_inserted, 0u) << indices.size() << " indices";
  }
  // Several meshes offering the same point: one copy.
  PolygonMesh target;
  target.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}};
  target.triangles = {0, 1, 2};
  PolygonMesh left, right;
  left.vertices = {{2, 2, 0}, {1, 3, 0}, {0, 3, 0}};
  left.triangles = {0, 1, 2};
  right.vertices = {{2, 2, 0}, {2, 3, 0}, {1, 3, 0}};
  right.triangles = {0, 1, 2};
  std::vector<PolygonMesh> three{target, left, right};
  repair_t_junctions(three, kTolerance);
  EXPECT_EQ(three[0].vertices.size(), 4u);
  EXPECT_EQ(three[0].triangles.size(), 6u);
}

// The real house: its floors meet along slanted basement-wall tops. After the pipeline's dicing and repair,
// no coplanar seam keeps a T-junction, and the rest of each polygon is untouched.
TEST(TJunctions, HouseFloorsHaveNoOpenSeams) {
  model::Model m = read_dxf(std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf");
  cut_openings(m);
  std::vector<PolygonMesh> meshes;
  std::vector<double> areas;
  for (const auto& p : m.polygons) {
    meshes.push_back(mesh_polygon(p, 0.4));
    areas.push_back(area(meshes.back()));
  }
  const std::size_t open_before = open_t_junctions(meshes);
  EXPECT_GT(open_before, 0u) << "the house has slanted seams between diced floors";
  const TJunctionStats s = repair_t_junctions(meshes, kTolerance);
  EXPECT_GT(s.vertices_inserted, 0u);
  EXPECT_EQ(open_t_junctions(meshes), 0u);
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    // Inserted points lie up to the tolerance off an edge: the area moves by at most that along the outline.
    EXPECT_NEAR(area(meshes[i]), areas[i], kTolerance * outline_length(meshes[i])) << "polygon " << i;
    EXPECT_TRUE(all_counter_clockwise(meshes[i])) << "polygon " << i;
  }
}

}  // namespace test_t_junctions
}  // namespace walk::compiler
