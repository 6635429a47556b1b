// Adaptive subdivision by direct light: where a lamp's falloff bends the light between a diced mesh's
// vertices, edges are split until linear interpolation meets the tolerance; the mesh stays conforming,
// oriented and of the same area, and a mesh no light reaches (or a panel) is left exactly as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <random>

#include "compiler/lighting/light_refinement.hpp"

namespace walk::compiler {
namespace test_light_refinement {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

constexpr double kSide = 4.0;    // metres: the floor
constexpr double kHeight = 0.5;  // metres: the lamp above its centre, so the light falls off sharply
constexpr double kPower = 100.0;

PolygonMesh floor_mesh(double grid) {
  model::Polygon p;
  p.vertices = {{0, 0, 0}, {kSide, 0, 0}, {kSide, kSide, 0}, {0, kSide, 0}};
  return mesh_polygon(p, grid);
}

model::Luminaire lamp() {
  model::Luminaire l;
  l.kind = model::LuminaireKind::Point;
  l.position = Vec3(kSide / 2, kSide / 2, kHeight);
  l.power = model::Rgb(kPower);
  return l;
}

// Closed form of the lamp's irradiance on the floor (luminance weights sum to 1 for grey light).
double exact(const Vec3& p) {
  const Vec3 d = lamp().position - p;
  const double r = glm::length(d);
  return kPower / (4.0 * std::numbers::pi) * kHeight / (r * r * r);
}

// Light the display would show at p: linear interpolation of the exact light at the corners of the
// triangle of `m` that holds p.
double interpolated(const PolygonMesh& m, const Vec3& p) {
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    const Vec3 a = m.vertices[m.triangles[t]], b = m.vertices[m.triangles[t + 1]],
               c = m.vertices[m.triangles[t + 2]];
    const double area = glm::cross(b - a, c - a).z;
    const double wa = glm::cross(b - p, c - p).z / area, wb = glm::cross(c - p, a - p).z / area;
    const double wc = 1.0 - wa - wb;
    constexpr double kInside = -1e-12;  // on an edge counts for either triangle
    if (wa >= kInside && wb >= kInside && wc >= kInside) return wa * exact(a) + wb * exact(b) + wc * exact(c);
  }
  ADD_FAILURE() << "no triangle holds " << p.x << " " << p.y;
  return 0.0;
}

double rms_interpolation_error(const PolygonMesh& m) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, kSide);
  double e2 = 0.0, s2 = 0.0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(u(rng), u(rng), 0.0);
    const double e = exact(p), shown = interpolated(m, p);
    e2 += (shown - e) * (shown - e);
    s2 += e * e;
  }
  return std::sqrt(e2 / s2);
}

TriangleBvh far_away_occluder() {
  return TriangleBvh({{Vec3(100, 100, 100), Vec3(101, 100, 100), Vec3(100, 101, 100), 0}});
}

TEST(LightRefinement, SplitsWhereTheFalloffBendsAndKeepsTheMeshWhole) {
  std::vector<PolygonMesh> meshes{floor_mesh(0.5)};
  const PolygonMesh before = meshes[0];
  LightRefinementOptions o;
  o.tolerance = 0.02;
  o.min_edge = 0.02;
  o.max_levels = 5;
  const auto stats = refine_by_direct_light(meshes, {true}, {lamp()}, far_away_occluder(), o);
  const PolygonMesh& m = meshes[0];
  EXPECT_GT(stats.edges_split, 0u);
  EXPECT_EQ(m.triangles.size() / 3, before.triangles.size() / 3 + stats.triangles_added);
  // The same area, every triangle facing +z: nothing folded or lost.
  double area = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    const double z = glm::cross(m.vertices[m.triangles[t + 1]] - m.vertices[m.triangles[t]],
                                m.vertices[m.triangles[t + 2]] - m.vertices[m.triangles[t]])
                         .z;
    EXPECT_GT(z, 0.0);
    area += 0.5 * z;
  }
  EXPECT_NEAR(area, kSide * kSide, 1e-9);
  // Conforming: an edge inside the square is used once each way; one on its boundary once (no T-junction).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    ++uses[{m.triangles[i], m.triangles[i % 3 == 2 ? i - 2 : i + 1]}];
  for (const auto& [edge, n] : uses) {
    EXPECT_EQ(n, 1);
    const Vec3 a = m.vertices[edge.first], b = m.vertices[edge.second];
    const Vec3 mid = (a + b) * 0.5;
    const bool on_boundary = mid.x < 1e-12 || mid.y < 1e-12 || mid.x > kSide - 1e-12 || mid.y > kSide - 1e-12;
    EXPECT_EQ(uses.count({edge.second, edge.first}), on_boundary ? 0u : 1u);
  }
  // Finer where the light is strong: the triangles under the lamp are smaller than those in the corners.
  const double error_before = rms_interpolation_error(before), error_after = rms_interpolation_error(m);
  std::printf(
      "lamp 0.5 m over a 4 m floor diced at 0.5 m: %zu -> %zu triangles, interpolation error %.2f%% -> "
      "%.2f%% RMS\n",
      before.triangles.size() / 3, m.triangles.size() / 3, 100.0 * error_before, 100.0 * error_after);
  EXPECT_LT(error_after, 0.25 * error_before);
  EXPECT_LT(error_after, 0.02);
  // No edge shorter than the shortest allowed.
  for (const auto& [edge, n] : uses)
    EXPECT_GE(glm::length(m.vertices[edge.first] - m.vertices[edge.second]), o.min_edge - 1e-12);
}

// The light the edges were tested with is handed back for every vertex of the refined mesh (the light stage
// shows it instead of gathering again): a point light's is exact, so it equals the closed form.
TEST(LightRefinement, HandsBackTheLightAtEveryRefinedVertex) {
  std::vector<PolygonMesh> meshes{floor_mesh(0.5), floor_mesh(0.5)};
  LightRefinementOptions o;
  o.tolerance = 0.02;
  std::vector<SparseLight> direct;
  const auto stats = refine_by_direct_light(meshes, {true, false}, {lamp()}, far_away_occluder(), o, &direct);
  ASSERT_GT(stats.edges_split, 0u);
  ASSERT_EQ(stats.circuits, 1u);
  ASSERT_EQ(direct.size(), 2u);
  EXPECT_TRUE(direct[1].empty());  // the panel: no receiver
  ASSERT_EQ(direct[0].rows(), meshes[0].vertices.size());
  // Gathering starts 0.1 mm off the surface (direct_light.cpp's shadow offset), 2e-4 of the lamp's 0.5 m
  // height.
  constexpr double kRelativeTolerance = 5e-4;
  for (std::size_t v = 0; v < meshes[0].vertices.size(); ++v)
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(direct[0].value(v, std::size_t(ch)), exact(meshes[0].vertices[v]),
                  kRelativeTolerance * exact(meshes[0].vertices[v]))
          << "vertex " << v;
}

TEST(LightRefinement, UnlitMeshesPanelsAndDarkScenesStayAsTheyWere) {
  std::vector<PolygonMesh> meshes{floor_mesh(0.5), floor_mesh(0.5)};
  const PolygonMesh before = meshes[0];
  LightRefinementOptions o;
  // The second mesh is a panel: not a receiver.
  (void)refine_by_direct_light(meshes, {true, false}, {lamp()}, far_away_occluder(), o);
  EXPECT_EQ(meshes[1].triangles, before.triangles);
  EXPECT_EQ(meshes[1].vertices, before.vertices);
  // No luminaire, or a lamp below the floor (the floor faces away): nothing to refine by.
  std::vector<PolygonMesh> dark{before};
  EXPECT_EQ(refine_by_direct_light(dark, {true}, {}, far_away_occluder(), o).edges_split, 0u);
  model::Luminaire under = lamp();
  under.position.z = -1.0;
  EXPECT_EQ(refine_by_direct_light(dark, {true}, {under}, far_away_occluder(), o).edges_split, 0u);
  EXPECT_EQ(dark[0].triangles, before.triangles);
}

// A 0.6 m panel hung 2 cm in front of the floor, facing away from it (a ceiling's lamp, upside down): the
// floor gets no direct light, yet every edge crossing the panel's outline is split down to the shortest
// length, since just inside the outline the floor sees the panel's back and just outside the whole room.
TEST(LightRefinement, EdgesCrossingTheOutlineOfAPanelHungJustInFrontAreSplit) {
  model::Luminaire panel;
  panel.position = Vec3(1.9, 2.1, 0.02);
  panel.normal = Vec3(0, 0, 1);
  panel.width = panel.height = 0.6;
  panel.power = model::Rgb(kPower);
  LightRefinementOptions o;
  o.min_edge = 0.2;  // edges of 0.4 m and more crossing the outline are split
  o.max_levels = 8;
  std::vector<PolygonMesh> meshes{floor_mesh(0.5)};
  const auto stats = refine_by_direct_light(meshes, {true}, {panel}, far_away_occluder(), o);
  EXPECT_GT(stats.outline_splits, 0u);
  EXPECT_EQ(stats.outline_splits, stats.edges_split) << "no direct light reaches the floor";
  auto covered = [&](const Vec3& p) {
    return std::abs(p.x - panel.position.x) <= 0.3 && std::abs(p.y - panel.position.y) <= 0.3;
  };
  const auto& m = meshes[0];
  double area = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    const Vec3 a = m.vertices[m.triangles[t]], b = m.vertices[m.triangles[t + 1]],
               c = m.vertices[m.triangles[t + 2]];
    area += 0.5 * glm::cross(b - a, c - a).z;
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      if (covered(p) != covered(q)) {
        EXPECT_LT(glm::length(q - p), 2.0 * o.min_edge);
      }
  }
  EXPECT_NEAR(area, kSide * kSide, 1e-9);

  // Hung farther than a few centimetres, or tilted, it is left to the light test (no light here: no split).
  for (const Vec3& move : {Vec3(0, 0, 0.5), Vec3(0, 0, 0)}) {
    model::Luminaire other = panel;
    other.position += move;
    if (glm::length(move) == 0.0) other.normal = glm::normalize(Vec3(1, 0, 1));
    std::vector<PolygonMesh> plain{floor_mesh(0.5)};
    EXPECT_EQ(refine_by_direct_light(plain, {true}, {other}, far_away_occluder(), o).outline_splits, 0u);
  }
}

}  // namespace test_light_refinement
}  // namespace walk::compiler
