// DXF entities beyond 3DFACE, on small drawings written here: thick lines, arcs, circles and polylines
// extruded along their OCS normal, polyface and polygon meshes, nested INSERT with scale, rotation, mirror
// and arrays, colours by layer/block/true colour, $INSUNITS, and located errors.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/geometry/mesher.hpp"
#include "compiler/import/dxf_geometry.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_dxf_entities {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// A DXF file from "code value" pairs; `sections` are written in order, each as (name, body).
std::string dxf(const std::vector<std::pair<std::string, std::string>>& sections) {
  std::string out;
  for (const auto& [name, body] : sections) out += "0\nSECTION\n2\n" + name + "\n" + body + "0\nENDSEC\n";
  return out + "0\nEOF\n";
}

std::string pairs(std::initializer_list<std::pair<int, std::string>> list) {
  std::string out;
  for (const auto& [code, value] : list) out += std::to_string(code) + "\n" + value + "\n";
  return out;
}

model::Model read(const std::string& text, DxfStats* stats = nullptr, DxfOptions options = {},
                  std::vector<DxfWire>* wires = nullptr) {
  std::istringstream in(text);
  return read_dxf(in, "test.dxf", options, stats, wires);
}

std::string error_of(const std::string& text) {
  try {
    (void)read(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

double area(const model::Polygon& p) {
  Vec3 n(0.0);
  for (std::size_t i = 1; i + 1 < p.vertices.size(); ++i)
    n += glm::cross(p.vertices[i] - p.vertices[0], p.vertices[i + 1] - p.vertices[0]);
  return 0.5 * glm::length(n);
}

double total_area(const model::Model& m) {
  double a = 0.0;
  for (const auto& p : m.polygons) a += area(p);
  return a;
}

constexpr double kEps = 1e-9;

TEST(DxfEntities, ThickLineIsAVerticalWall) {
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "LINE"},
                                               {8, "walls"},
                                               {10, "0"},
                                               {20, "0"},
                                               {30, "0"},
                                               {11, "4"},
                                               {21, "0"},
                                               {31, "0"},
                                               {39, "2.5"}})}}));
  ASSERT_EQ(m.polygons.size(), 1u);
  EXPECT_NEAR(area(m.polygons[0]), 10.0, kEps);
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.max.z, 2.5, kEps);
  EXPECT_EQ(m.groups[m.polygons[0].group], "walls");
}

TEST(DxfEntities, LineWithoutThicknessIsAWire) {
  std::vector<DxfWire> wires;
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "LINE"}, {10, "0"}, {20, "0"}, {11, "4"}, {21, "3"}})}}),
                      nullptr, {}, &wires);
  EXPECT_TRUE(m.polygons.empty());
  ASSERT_EQ(wires.size(), 1u);
  EXPECT_NEAR(glm::distance(wires[0].a, wires[0].b), 5.0, kEps);
}

TEST(DxfEntities, ThickCircleIsACylinderOfQuads) {
  const auto m = read(
      dxf({{"ENTITIES", pairs({{0, "CIRCLE"}, {10, "1"}, {20, "2"}, {30, "0"}, {40, "0.5"}, {39, "3"}})}}));
  ASSERT_EQ(m.polygons.size(), static_cast<std::size_t>(kDxfSegmentsPerCircle));
  const double side = 2.0 * 0.5 * std::sin(std::numbers::pi / kDxfSegmentsPerCircle);
  EXPECT_NEAR(total_area(m), kDxfSegmentsPerCircle * side * 3.0, 1e-9);
  // Faces point away from the axis: outward.
  for (const auto& p : m.polygons) {
    Vec3 c(0.0);
    for (const auto& v : p.vertices) c += v / 4.0;
    EXPECT_GT(glm::dot(polygon_normal(p.vertices), c - Vec3(1, 2, c.z)), 0.0);
  }
}

TEST(DxfEntities, ArcSweepsCounterClockwiseFromStartToEnd) {
  const auto m =
      read(dxf({{"ENTITIES",
                 pairs({{0, "ARC"}, {10, "0"}, {20, "0"}, {40, "2"}, {50, "0"}, {51, "90"}, {39, "1"}})}}));
  ASSERT_EQ(m.polygons.size(), static_cast<std::size_t>(kDxfSegmentsPerCircle / 4));
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.min.x, 0.0, 1e-12);
  EXPECT_NEAR(b.min.y, 0.0, 1e-12);
  EXPECT_NEAR(b.max.x, 2.0, 1e-12);
  EXPECT_NEAR(b.max.y, 2.0, 1e-12);
}

TEST(DxfEntities, LwpolylineWithBulgeAndThickness) {
  // A closed 4 x 2 rectangle whose top edge is a half circle bulging up (bulge 1 = 180 degrees).
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "LWPOLYLINE"},
                                               {90, "4"},
                                               {70, "1"},
                                               {39, "1"},
                                               {10, "0"},
                                               {20, "0"},
                                               {10, "4"},
                                               {20, "0"},
                                               {10, "4"},
                                               {20, "2"},
                                               {42, "1"},
                                               {10, "0"},
                                               {20, "2"}})}}));
  // 3 straight sides + 16 chords of the half circle.
  EXPECT_EQ(m.polygons.size(), 3u + kDxfSegmentsPerCircle / 2);
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.max.y, 4.0, 1e-9);  // the half circle of radius 2 over the top edge centred at (2, 2)
  EXPECT_NEAR(b.min.x, 0.0, 1e-9);
  EXPECT_NEAR(b.max.x, 4.0, 1e-9);
}

TEST(DxfEntities, ArbitraryAxisFlipsXForADownwardNormal) {
  // With extrusion (0, 0, -1) the OCS x axis is world -x: a thick line from OCS x 1..2 lies at world x -2..-1
  // and its thickness goes down.
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "LWPOLYLINE"},
                                               {90, "2"},
                                               {70, "0"},
                                               {39, "1"},
                                               {38, "0"},
                                               {10, "1"},
                                               {20, "0"},
                                               {10, "2"},
                                               {20, "0"},
                                               {210, "0"},
                                               {220, "0"},
                                               {230, "-1"}})}}));
  ASSERT_EQ(m.polygons.size(), 1u);
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.min.x, -2.0, kEps);
  EXPECT_NEAR(b.max.x, -1.0, kEps);
  EXPECT_NEAR(b.min.z, -1.0, kEps);
  EXPECT_NEAR(b.max.z, 0.0, kEps);
}

TEST(DxfEntities, ArbitraryAxisForATiltedNormal) {
  // Normal along +x: |Nx| >= 1/64, so OCS x = world z x N = (0, 1, 0), OCS y = N x Ax = (0, 0, 1).
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "CIRCLE"},
                                               {10, "0"},
                                               {20, "0"},
                                               {30, "5"},
                                               {40, "1"},
                                               {39, "2"},
                                               {210, "1"},
                                               {220, "0"},
                                               {230, "0"}})}}));
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.min.x, 5.0, kEps);  // elevation 5 along the normal
  EXPECT_NEAR(b.max.x, 7.0, kEps);  // plus thickness 2
  EXPECT_NEAR(b.max.y, 1.0, kEps);
  EXPECT_NEAR(b.max.z, 1.0, kEps);
}

std::string polyface_cube() {
  std::string body = pairs({{0, "POLYLINE"}, {66, "1"}, {70, "64"}, {71, "8"}, {72, "6"}});
  const int corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                             {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& c : corners)
    body += pairs({{0, "VERTEX"},
                   {10, std::to_string(c[0])},
                   {20, std::to_string(c[1])},
                   {30, std::to_string(c[2])},
                   {70, "192"}});
  // Outward faces, counter-clockwise seen from outside; a negative index hides an edge and still counts.
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                           {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, -8}};
  for (const auto& f : faces)
    body += pairs({{0, "VERTEX"},
                   {10, "0"},
                   {20, "0"},
                   {30, "0"},
                   {70, "128"},
                   {71, std::to_string(f[0])},
                   {72, std::to_string(f[1])},
                   {73, std::to_string(f[2])},
                   {74, std::to_string(f[3])}});
  return body + pairs({{0, "SEQEND"}});
}

void expect_outward_cube(const model::Model& m, Vec3 centre) {
  ASSERT_EQ(m.polygons.size(), 6u);
  for (const auto& p : m.polygons) {
    Vec3 c(0.0);
    for (const auto& v : p.vertices) c += v / static_cast<double>(p.vertices.size());
    EXPECT_GT(glm::dot(polygon_normal(p.vertices), c - centre), 0.0)
        << "face at " << c.x << " " << c.y << " " << c.z;
  }
}

TEST(DxfEntities, PolyfaceMeshCube) {
  const auto m = read(dxf({{"ENTITIES", polyface_cube()}}));
  expect_outward_cube(m, Vec3(0.5));
  EXPECT_NEAR(total_area(m), 6.0, kEps);
}

TEST(DxfEntities, PolyfaceIndexOutOfRangeNamesItsLine) {
  std::string body = pairs({{0, "POLYLINE"}, {66, "1"}, {70, "64"}});
  body += pairs({{0, "VERTEX"}, {10, "0"}, {20, "0"}, {30, "0"}, {70, "192"}});
  body += pairs({{0, "VERTEX"}, {70, "128"}, {71, "1"}, {72, "2"}, {73, "9"}}) + pairs({{0, "SEQEND"}});
  const std::string e = error_of(dxf({{"ENTITIES", body}}));
  EXPECT_NE(e.find("test.dxf:21:"), std::string::npos) << e;  // the face VERTEX's line
  EXPECT_NE(e.find("refers to vertex 2 but only 1 vertices precede it"), std::string::npos) << e;
}

TEST(DxfEntities, PolygonMeshGrid) {
  // A 3 x 2 vertex mesh: 2 x 1 quads over a 2 x 1 plane.
  std::string body = pairs({{0, "POLYLINE"}, {66, "1"}, {70, "16"}, {71, "3"}, {72, "2"}});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j)
      body += pairs({{0, "VERTEX"}, {10, std::to_string(i)}, {20, std::to_string(j)}, {30, "0"}, {70, "64"}});
  const auto m = read(dxf({{"ENTITIES", body + pairs({{0, "SEQEND"}})}}));
  EXPECT_EQ(m.polygons.size(), 2u);
  EXPECT_NEAR(total_area(m), 2.0, kEps);
}

// A block "CUBE" holding the polyface cube (base point 0.5, 0.5, 0), placed by INSERT pairs.
std::string blocks(const std::string& extra = {}) {
  return pairs({{0, "BLOCK"}, {8, "0"}, {2, "CUBE"}, {70, "0"}, {10, "0.5"}, {20, "0.5"}, {30, "0"}}) +
         polyface_cube() + pairs({{0, "ENDBLK"}}) + extra;
}

TEST(DxfEntities, InsertScalesRotatesAndArrays) {
  // 2 columns x 3 rows, spacing 10 x 20 in the block's rotated frame, rotation 90 degrees, scale 2.
  const auto m = read(dxf({{"BLOCKS", blocks()},
                           {"ENTITIES", pairs({{0, "INSERT"},
                                               {2, "CUBE"},
                                               {10, "100"},
                                               {20, "0"},
                                               {30, "0"},
                                               {41, "2"},
                                               {42, "2"},
                                               {43, "2"},
                                               {50, "90"},
                                               {70, "2"},
                                               {71, "3"},
                                               {44, "10"},
                                               {45, "20"}})}}));
  ASSERT_EQ(m.polygons.size(), 36u);
  EXPECT_NEAR(total_area(m), 6 * 6 * 4.0, 1e-9);
  const model::Bounds b = bounds_of(m);
  // Columns run along rotated x = world y (0, 10), rows along rotated y = world -x (0, -20, -40).
  EXPECT_NEAR(b.min.x, 100.0 - 40.0 - 1.0, 1e-9);
  EXPECT_NEAR(b.max.x, 100.0 + 1.0, 1e-9);
  EXPECT_NEAR(b.min.y, -1.0, 1e-9);
  EXPECT_NEAR(b.max.y, 10.0 + 1.0, 1e-9);
  EXPECT_NEAR(b.max.z, 2.0, 1e-9);
}

TEST(DxfEntities, NestedInsertWithNegativeScaleKeepsOutwardNormals) {
  // Block "TWO" places CUBE mirrored in x (a mirror); the drawing places TWO with y and z scales negative (a
  // half turn about x, not a mirror) and stretched: the cube ends up mirrored once, upside down.
  const std::string two = pairs({{0, "BLOCK"}, {2, "TWO"}, {10, "0"}, {20, "0"}, {30, "0"}}) +
                          pairs({{0, "INSERT"}, {2, "CUBE"}, {10, "5"}, {20, "0"}, {30, "0"}, {41, "-1"}}) +
                          pairs({{0, "ENDBLK"}});
  DxfStats stats;
  const auto m = read(
      dxf({{"BLOCKS", blocks(two)},
           {"ENTITIES",
            pairs({{0, "INSERT"}, {2, "TWO"}, {10, "0"}, {20, "0"}, {30, "0"}, {42, "-1"}, {43, "-3"}})}}),
      &stats);
  EXPECT_EQ(stats.block_instances, 2u);
  EXPECT_EQ(stats.mirrored_instances, 1u);
  // The cube: x 4.5..5.5 mirrored about 5 stays 4.5..5.5; y -0.5..0.5 mirrored; z 0..1 becomes 0..-3.
  expect_outward_cube(m, Vec3(5.0, 0.0, -1.5));
  EXPECT_NEAR(total_area(m), 2 * 1.0 + 4 * 3.0, 1e-9);
}

TEST(DxfEntities, ColoursByLayerByBlockAndTrueColour) {
  const std::string tables = pairs({{0, "TABLE"},
                                    {2, "LAYER"},
                                    {0, "LAYER"},
                                    {2, "red"},
                                    {70, "0"},
                                    {62, "1"},
                                    {0, "LAYER"},
                                    {2, "frozen"},
                                    {70, "1"},
                                    {62, "5"},
                                    {0, "ENDTAB"}});
  const std::string face = pairs({{10, "0"},
                                  {20, "0"},
                                  {30, "0"},
                                  {11, "1"},
                                  {21, "0"},
                                  {31, "0"},
                                  {12, "1"},
                                  {22, "1"},
                                  {32, "0"},
                                  {13, "0"},
                                  {23, "1"},
                                  {33, "0"}});
  const std::string block =
      pairs({{0, "BLOCK"}, {2, "B"}, {10, "0"}, {20, "0"}, {30, "0"}, {0, "3DFACE"}, {8, "0"}, {62, "0"}}) +
      face + pairs({{0, "ENDBLK"}});
  DxfStats stats;
  const auto m =
      read(dxf({{"TABLES", tables},
                {"BLOCKS", block},
                {"ENTITIES", pairs({{0, "3DFACE"}, {8, "red"}}) + face +                         // BYLAYER
                                 pairs({{0, "3DFACE"}, {8, "red"}, {420, "16744448"}}) + face +  // FF8000
                                 pairs({{0, "3DFACE"}, {8, "frozen"}}) + face +
                                 pairs({{0, "INSERT"}, {2, "B"}, {8, "red"}, {62, "3"}})}}),
           &stats);
  ASSERT_EQ(m.polygons.size(), 3u);
  EXPECT_EQ(stats.frozen, 1u);
  EXPECT_EQ(m.polygons[0].color, 1);
  EXPECT_EQ(m.polygons[1].color, 1);
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[1].name, "rgb:FF8000");
  EXPECT_NEAR(m.materials[1].reflectance.g, 128.0 / 255.0, 1e-12);
  EXPECT_EQ(m.polygons[1].material, 1u);
  EXPECT_EQ(m.polygons[2].color, 3);                // BYBLOCK: the INSERT's colour
  EXPECT_EQ(m.groups[m.polygons[2].group], "red");  // layer 0 in a block: the INSERT's layer
  EXPECT_EQ(stats.true_colours, 1u);
}

TEST(DxfEntities, InsunitsSetsTheScaleUnlessTheSceneGivesOne) {
  const std::string text =
      dxf({{"HEADER", pairs({{9, "$INSUNITS"}, {70, "4"}})},
           {"ENTITIES", pairs({{0, "LINE"}, {10, "0"}, {20, "0"}, {11, "1000"}, {21, "0"}, {39, "1000"}})}});
  DxfStats stats;
  const auto mm = read(text, &stats, {1.0, true});
  EXPECT_EQ(stats.insunits, 4);
  EXPECT_DOUBLE_EQ(stats.unit_scale, 0.001);
  EXPECT_NEAR(area(mm.polygons[0]), 1.0, 1e-12);
  const auto forced = read(text, &stats, {0.01, false});
  EXPECT_NEAR(area(forced.polygons[0]), 100.0, 1e-9);
}

TEST(DxfEntities, SolidCornersAreInZOrder) {
  const auto m = read(dxf({{"ENTITIES", pairs({{0, "SOLID"},
                                               {10, "0"},
                                               {20, "0"},
                                               {11, "1"},
                                               {21, "0"},
                                               {12, "0"},
                                               {22, "1"},
                                               {13, "1"},
                                               {23, "1"}})}}));
  ASSERT_EQ(m.polygons.size(), 1u);
  EXPECT_NEAR(area(m.polygons[0]), 1.0, kEps);  // not a bow tie
}

TEST(DxfEntities, UndefinedBlockNamesItsInsertLine) {
  const std::string e = error_of(dxf({{"ENTITIES", pairs({{0, "INSERT"}, {2, "NOPE"}})}}));
  EXPECT_NE(e.find("test.dxf:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("NOPE"), std::string::npos) << e;
}

TEST(DxfEntities, SelfInsertingBlockIsAnErrorNotAHang) {
  const std::string loop = pairs({{0, "BLOCK"}, {2, "L"}, {0, "INSERT"}, {2, "L"}, {0, "ENDBLK"}});
  const std::string e = error_of(dxf({{"BLOCKS", loop}, {"ENTITIES", pairs({{0, "INSERT"}, {2, "L"}})}}));
  EXPECT_NE(e.find("nested more than"), std::string::npos) << e;
  EXPECT_NE(e.find("test.dxf:"), std::string::npos) << e;
}

TEST(DxfEntities, HugeArrayIsAnErrorNotAnOutOfMemory) {
  const std::string e = error_of(
      dxf({{"BLOCKS", blocks()},
           {"ENTITIES",
            pairs({{0, "INSERT"}, {2, "CUBE"}, {70, "32767"}, {71, "32767"}, {44, "1"}, {45, "1"}})}}));
  EXPECT_NE(e.find("INSERT arrays"), std::string::npos) << e;
}

TEST(DxfEntities, NestedArrayBombIsRefusedBeforeExpanding) {
  // 100 x 100 copies of a block that is 100 x 100 cubes: 1e8 cubes, counted (not built) and refused.
  const std::string nested = blocks() + pairs({{0, "BLOCK"},
                                               {2, "GRID"},
                                               {0, "INSERT"},
                                               {2, "CUBE"},
                                               {70, "100"},
                                               {71, "100"},
                                               {44, "1"},
                                               {45, "1"},
                                               {0, "ENDBLK"}});
  const auto start = std::chrono::steady_clock::now();
  const std::string e = error_of(
      dxf({{"BLOCKS", nested},
           {"ENTITIES",
            pairs({{0, "INSERT"}, {2, "GRID"}, {70, "100"}, {71, "100"}, {44, "100"}, {45, "100"}})}}));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(e.find("would expand to"), std::string::npos) << e;
  EXPECT_NE(e.find("test.dxf:"), std::string::npos) << e;
  EXPECT_LT(seconds, 2.0) << "refused before building (milliseconds; generous for a loaded CI machine)";
}

TEST(DxfEntities, NonFiniteCoordinateIsAnError) {
  const std::string e =
      error_of(dxf({{"ENTITIES", pairs({{0, "LINE"}, {10, "nan"}, {11, "1"}, {39, "1"}})}}));
  EXPECT_NE(e.find("test.dxf:8:"), std::string::npos) << e;
  EXPECT_NE(e.find("finite"), std::string::npos) << e;
}

}  // namespace test_dxf_entities
}  // namespace walk::compiler
