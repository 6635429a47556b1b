// Quake brushes: faces by plane intersection, CSG between brushes, nearly degenerate plane sets, the .map
// parser's located errors, lights and circuits, on small maps written here.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <string>

#include "compiler/geometry/mesher.hpp"
#include "compiler/import/brush_csg.hpp"
#include "compiler/import/brush_geometry.hpp"
#include "compiler/import/map_reader.hpp"
#include "compiler/pipeline.hpp"
#include "compiler/stages/stage.hpp"
#include "compiler/stages/stages.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_quake_brushes {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
using Points = std::array<Vec3, 3>;

// The six planes of an axis-aligned box in Quake's point order (normal (p0-p1) x (p2-p1) points out).
std::vector<Points> box(Vec3 lo, Vec3 hi) {
  return {
      {Vec3(lo.x, 0, 0), Vec3(lo.x, 1, 0), Vec3(lo.x, 0, 1)},  // -x: (0,-1,0) x (0,-1,1) = (-1,0,0)
      {Vec3(hi.x, 0, 0), Vec3(hi.x, 0, 1), Vec3(hi.x, 1, 0)},  // +x
      {Vec3(0, lo.y, 0), Vec3(0, lo.y, 1), Vec3(1, lo.y, 0)},  // -y
      {Vec3(0, hi.y, 0), Vec3(1, hi.y, 0), Vec3(0, hi.y, 1)},  // +y
      {Vec3(0, 0, lo.z), Vec3(1, 0, lo.z), Vec3(0, 1, lo.z)},  // -z
      {Vec3(0, 0, hi.z), Vec3(0, 1, hi.z), Vec3(1, 0, hi.z)},  // +z
  };
}

double area(const std::vector<Vec3>& w) {
  Vec3 n(0.0);
  for (std::size_t i = 1; i + 1 < w.size(); ++i) n += glm::cross(w[i] - w[0], w[i + 1] - w[0]);
  return 0.5 * glm::length(n);
}

// Every directed edge of a closed brush surface has its reverse in another face: no cracks.
void expect_closed(const ConvexBrush& b) {
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
  const auto key = [](const Vec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
  for (const auto& f : b.faces)
    for (std::size_t i = 0; i < f.winding.size(); ++i)
      ++edges[{key(f.winding[i]), key(f.winding[(i + 1) % f.winding.size()])}];
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    const auto twin = edges.find({e.second, e.first});
    EXPECT_TRUE(twin != edges.end()) << "crack along an edge from " << e.first[0] << " " << e.first[1] << " "
                                     << e.first[2];
  }
}

TEST(QuakeBrushes, BoxFacesPointOutAndCloseTheVolume) {
  ConvexBrush b;
  BrushStats s;
  ASSERT_TRUE(build_brush(box({0, 0, 0}, {64, 32, 16}), b, s));
  ASSERT_EQ(b.faces.size(), 6u);
  double total = 0.0;
  for (const auto& f : b.faces) {
    total += area(f.winding);
    EXPECT_GT(glm::dot(polygon_normal(f.winding), b.planes[f.plane].normal), 0.999);
  }
  EXPECT_DOUBLE_EQ(total, 2.0 * (64 * 32 + 64 * 16 + 32 * 16));
  expect_closed(b);
}

TEST(QuakeBrushes, NearlyCoincidentPlaneGivesNoSliverAndNoCrack) {
  // A box with a seventh plane that cuts its top +x edge by 1e-4 units (a bevel far thinner than the weld
  // distance): exact intersection would make a face 1e-4 wide; welding removes it and the neighbours close.
  auto planes = box({0, 0, 0}, {64, 64, 64});
  const double cut = 1e-4;
  planes.push_back({Vec3(64 - cut, 0, 64), Vec3(64 - cut, 64, 64), Vec3(64, 0, 64 - cut)});
  ConvexBrush b;
  BrushStats s;
  ASSERT_TRUE(build_brush(planes, b, s));
  EXPECT_EQ(b.faces.size(), 6u);  // the bevel face is gone (clipped away or welded to nothing)
  for (const auto& f : b.faces) {
    // No face thinner than the weld distance: its area over its longest edge.
    double longest = 0.0;
    for (std::size_t i = 0; i < f.winding.size(); ++i)
      longest = std::max(longest, glm::distance(f.winding[i], f.winding[(i + 1) % f.winding.size()]));
    EXPECT_GT(area(f.winding) / longest, kBrushWeld);
  }
  expect_closed(b);
}

TEST(QuakeBrushes, NearlyParallelPlanesMeetFarAwayOrNotAtAll) {
  // Two side planes tilted by 1e-7 rad towards each other: their intersection lies far outside the box and
  // the brush stays a closed box of the right size.
  auto planes = box({0, 0, 0}, {64, 64, 64});
  planes[1] = {Vec3(64, 0, 0), Vec3(64 + 64e-7, 0, 64), Vec3(64, 64, 0)};
  ConvexBrush b;
  BrushStats s;
  ASSERT_TRUE(build_brush(planes, b, s));
  EXPECT_EQ(b.faces.size(), 6u);
  expect_closed(b);
  EXPECT_NEAR(b.bounds.max.x, 64.0, 1e-3);
}

TEST(QuakeBrushes, CollinearPlanePointsAndOpenBrushesAreCounted) {
  auto planes = box({0, 0, 0}, {8, 8, 8});
  planes.push_back({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)});
  ConvexBrush b;
  BrushStats s;
  EXPECT_TRUE(build_brush(planes, b, s));
  EXPECT_EQ(s.degenerate_planes, 1u);
  planes = box({0, 0, 0}, {8, 8, 8});
  planes.pop_back();  // no top: unbounded
  EXPECT_FALSE(build_brush(planes, b, s));
  EXPECT_EQ(s.open_brushes, 1u);
}

double csg_area(const std::vector<std::vector<Points>>& boxes, std::size_t* hidden = nullptr) {
  std::vector<ConvexBrush> brushes(boxes.size());
  BrushStats s;
  for (std::size_t i = 0; i < boxes.size(); ++i) EXPECT_TRUE(build_brush(boxes[i], brushes[i], s));
  CsgStats cs;
  double total = 0.0;
  for (const auto& f : csg_faces(brushes, std::vector<bool>(boxes.size(), true), cs))
    total += area(f.winding);
  if (hidden) *hidden = cs.faces_hidden;
  return total;
}

TEST(QuakeBrushes, CsgRemovesTouchingFacesAndHiddenParts) {
  // Two 2x1x1 boxes side by side: the two touching faces vanish; the result is the 4x1x1 box's surface.
  std::size_t hidden = 0;
  EXPECT_NEAR(csg_area({box({0, 0, 0}, {2, 1, 1}), box({2, 0, 0}, {4, 1, 1})}, &hidden), 2 * (4 + 4 + 1),
              1e-9);
  EXPECT_EQ(hidden, 2u);
  // Overlapping boxes: the surface of their union (an L-free 3x1x1 bar).
  EXPECT_NEAR(csg_area({box({0, 0, 0}, {2, 1, 1}), box({1, 0, 0}, {3, 1, 1})}), 2 * (3 + 3 + 1), 1e-9);
  // Identical boxes: one copy of each face is kept.
  EXPECT_NEAR(csg_area({box({0, 0, 0}, {1, 1, 1}), box({0, 0, 0}, {1, 1, 1})}), 6.0, 1e-9);
  // A box inside another: wholly hidden.
  EXPECT_NEAR(csg_area({box({0, 0, 0}, {4, 4, 4}), box({1, 1, 1}, {2, 2, 2})}), 6 * 16.0, 1e-9);
}

std::string error_of(const std::string& text) {
  try {
    (void)read_map_text(text, "t.map", {}, nullptr);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kRoom = R"({
"classname" "worldspawn"
"mapversion" "220"
{
( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) WALL [ 0 1 0 0 ] [ 0 0 -1 0 ] 0 1 1
( 64 0 0 ) ( 64 0 1 ) ( 64 1 0 ) WALL [ 0 1 0 0 ] [ 0 0 -1 0 ] 0 1 1
( 0 0 0 ) ( 0 0 1 ) ( 1 0 0 ) WALL [ 1 0 0 0 ] [ 0 0 -1 0 ] 0 1 1
( 0 64 0 ) ( 1 64 0 ) ( 0 64 1 ) WALL [ 1 0 0 0 ] [ 0 0 -1 0 ] 0 1 1
( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) FLOOR [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1
( 0 0 8 ) ( 0 1 8 ) ( 1 0 8 ) sky1 [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1
}
}
{
"classname" "light"
"origin" "32 32 100"
"light" "200"
"_color" "1 0.5 0.25"
"style" "5"
}
{
"classname" "light"
"origin" "8 8 100"
"targetname" "t1"
"spawnflags" "1"
}
{
"classname" "light"
"origin" "16 8 100"
"targetname" "t1"
"target" "spot"
}
{
"classname" "info_null"
"origin" "16 8 0"
"targetname" "spot"
}
{
"classname" "func_door"
{
( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) DOOR 0 0 0 1 1
( 4 0 0 ) ( 4 0 1 ) ( 4 1 0 ) DOOR 0 0 0 1 1
( 0 0 0 ) ( 0 0 1 ) ( 1 0 0 ) DOOR 0 0 0 1 1
( 0 4 0 ) ( 1 4 0 ) ( 0 4 1 ) DOOR 0 0 0 1 1
( 0 0 8 ) ( 1 0 8 ) ( 0 1 8 ) DOOR 0 0 0 1 1
( 0 0 12 ) ( 0 1 12 ) ( 1 0 12 ) DOOR 0 0 0 1 1
}
}
{
"classname" "trigger_once"
{
( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) trigger 0 0 0 1 1
( 4 0 0 ) ( 4 0 1 ) ( 4 1 0 ) trigger 0 0 0 1 1
( 0 0 0 ) ( 0 0 1 ) ( 1 0 0 ) trigger 0 0 0 1 1
( 0 4 0 ) ( 1 4 0 ) ( 0 4 1 ) trigger 0 0 0 1 1
( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) trigger 0 0 0 1 1
( 0 0 4 ) ( 0 1 4 ) ( 1 0 4 ) trigger 0 0 0 1 1
}
}
)";

TEST(QuakeMap, RolesLightsAndCircuits) {
  MapStats s;
  const auto m = read_map_text(kRoom, "t.map", {0.0254}, &s);
  EXPECT_TRUE(s.valve220);
  EXPECT_EQ(s.brushes, 3u);
  EXPECT_EQ(s.trigger_brushes, 1u);
  EXPECT_EQ(s.door_brushes, 1u);
  std::map<model::Role, int> roles;
  for (const auto& p : m.polygons) ++roles[p.role];
  EXPECT_EQ(roles[model::Role::Opening], 5);  // the door's underside lies on the world's top: hidden
  EXPECT_EQ(roles[model::Role::Ignored], 0);
  EXPECT_EQ(roles[model::Role::Opaque], 6);  // the sky among them, black
  EXPECT_EQ(s.sky_faces, 1u);
  for (const auto& p : m.polygons) {
    if (p.name == "sky1") {
      EXPECT_EQ(m.materials[p.material].reflectance, model::Rgb(0.0));
    }
  }
  // The world's one brush is the model's one solid, a closed box of six faces in metres.
  ASSERT_EQ(m.solids.size(), 1u);
  EXPECT_EQ(m.solids[0].faces.size(), 6u);
  ASSERT_EQ(m.luminaires.size(), 3u);
  ASSERT_EQ(m.circuits.size(), 2u);  // "style 5" and "switch t1"
  EXPECT_EQ(m.circuits[0].name, "style 5");
  EXPECT_EQ(m.circuits[1].name, "switch t1");
  EXPECT_EQ(m.circuits[1].default_level, 1.0);  // one of its two lights starts on
  EXPECT_EQ(m.luminaires[0].kind, model::LuminaireKind::Point);
  EXPECT_NEAR(m.luminaires[0].power.r, 200 * kWattsPerQuakeLight, 1e-12);
  EXPECT_NEAR(m.luminaires[0].power.b, 0.25 * 200 * kWattsPerQuakeLight, 1e-12);
  EXPECT_NEAR(m.luminaires[0].position.z, 100 * 0.0254, 1e-12);
  EXPECT_EQ(m.luminaires[2].kind, model::LuminaireKind::Spot);
  EXPECT_NEAR(m.luminaires[2].normal.z, -1.0, 1e-12);
  EXPECT_NEAR(m.luminaires[2].cone, 10.0 * std::acos(-1.0) / 180.0, 1e-12);
  // Same texture, same colour; different textures, (almost surely) different colours.
  EXPECT_EQ(texture_reflectance("WALL"), texture_reflectance("wall"));
  EXPECT_NE(texture_reflectance("WALL"), texture_reflectance("FLOOR"));
}

// A brush as .map text: its box's six planes, one texture.
std::string brush_text(Vec3 lo, Vec3 hi, const std::string& texture) {
  std::string text = "{\n";
  for (const auto& plane : box(lo, hi)) {
    for (const auto& p : plane)
      text += "( " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " ) ";
    text += texture + " 0 0 0 1 1\n";
  }
  return text + "}\n";
}

// A floor slab over a pool of slime 8 units (0.2 m) below it: the slime's surface lies within the
// openings stage's depth for a window recessed into a wall. The CSG has already made the level's faces
// disjoint, so the stage leaves a Quake model alone and the slab keeps its underside; cutting it would open a
// hole through which a viewer in the slime sees into the slab and beyond (E1M1 missed pixels so).
TEST(QuakeMap, LiquidBelowAFloorCutsNoHoleInIt) {
  const std::string text = "{\n\"classname\" \"worldspawn\"\n" +
                           brush_text({0, 0, 0}, {64, 64, 16}, "FLOOR") +
                           brush_text({0, 0, -64}, {64, 64, -8}, "*SLIME0") + "}\n";
  const model::Model read = read_map_text(text, "t.map", {0.0254}, nullptr);
  EXPECT_TRUE(read.csg_merged);
  auto underside = [](const model::Model& m) {
    double area_m2 = 0.0;
    for (const auto& p : m.polygons) {
      bool on = p.role == model::Role::Opaque;
      for (const auto& v : p.vertices) on = on && std::abs(v.z) < 1e-9;
      if (on) area_m2 += area(p.vertices);
    }
    return area_m2;
  };
  const double slab_m2 = std::pow(64 * 0.0254, 2);
  ASSERT_NEAR(underside(read), slab_m2, 1e-9);

  SceneConfig config;
  CompileOptions options;
  model::BundleContents out;
  CompileState state(config, options, nullptr, out);
  state.model = read;
  (void)openings_stage()->run(state, 0);
  EXPECT_NEAR(underside(state.model), slab_m2, 1e-9) << "the slab keeps its underside";
  // What the flag guards against: without it, the slime's surface is taken for a window recessed 0.2 m
  // behind the slab's underside, and cut out of it whole.
  model::Model unmarked = read;
  unmarked.csg_merged = false;
  state.model = unmarked;
  (void)openings_stage()->run(state, 0);
  EXPECT_LT(underside(state.model), 0.01 * slab_m2);
}

TEST(QuakeMap, ErrorsNameTheLine) {
  EXPECT_NE(error_of("{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 0 1 0 ) ( 0 0 x ) T 0 0 0 1 1\n}\n}\n")
                .find("t.map:4:"),
            std::string::npos);
  EXPECT_NE(error_of("{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 0 1 0 ) ( 0 0 1 ) T 0 0 0 1 1\n")
                .find("t.map:"),
            std::string::npos);
  EXPECT_NE(error_of("{\n\"classname\" \"worldspawn\n}\n").find("t.map:2:"), std::string::npos);
  EXPECT_NE(error_of("x").find("t.map:1:"), std::string::npos);
  EXPECT_NE(error_of("").find("no entities"), std::string::npos);
  EXPECT_NE(error_of("{\n\"classname\" \"light\"\n\"origin\" \"1 2\"\n}\n").find("t.map:1:"),
            std::string::npos);
}

}  // namespace test_quake_brushes
}  // namespace walk::compiler
