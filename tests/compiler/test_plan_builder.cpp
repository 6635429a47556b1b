// 2D plan to 3D on a plan drawn here: two rooms, an inner doorway, an entrance, a window.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>

#include "compiler/geometry/mesher.hpp"
#include "compiler/import/plan_builder.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_plan_builder {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Walls as abutting rectangles, each drawn as its closed outline (as a CAD plan draws wall pieces).
std::vector<DxfWire> two_rooms() {
  const double r[][4] = {{0, 0, 0.2, 3.4},     {8.2, 0, 8.4, 3.4},  {0.2, 3.2, 8.2, 3.4},  // left, right, top
                         {0.2, 0, 6.0, 0.2},   {7.0, 0, 8.2, 0.2},     // bottom, entrance gap 6..7
                         {4.1, 0.2, 4.3, 1.0}, {4.1, 1.9, 4.3, 3.2}};  // middle, door gap 1..1.9
  std::vector<DxfWire> wires;
  for (const auto& q : r) {
    const Vec3 c[4] = {{q[0], q[1], 0}, {q[2], q[1], 0}, {q[2], q[3], 0}, {q[0], q[3], 0}};
    for (int k = 0; k < 4; ++k) wires.push_back({c[k], c[(k + 1) % 4], 0, 0});
  }
  return wires;
}

double area(const model::Polygon& p) {
  Vec3 n(0.0);
  for (std::size_t i = 1; i + 1 < p.vertices.size(); ++i)
    n += glm::cross(p.vertices[i] - p.vertices[0], p.vertices[i + 1] - p.vertices[0]);
  return 0.5 * glm::length(n);
}

TEST(PlanBuilder, TwoRoomsDoorwaysAndAWindow) {
  PlanOptions o;
  o.wall_height = 2.5;
  o.door_height = 2.0;
  o.windows.push_back({{2.0, 3.4, 0.0}, 1.2, 0.9, 2.1});
  PlanStats s;
  const model::Model m = build_plan(two_rooms(), o, "plan.dxf", &s);
  EXPECT_GE(s.loops, 1u);  // outlines that share corners may be walked as one closed loop
  EXPECT_LE(s.loops, 7u);
  EXPECT_EQ(s.open_wires, 0u);
  EXPECT_EQ(s.doorways, 2u);
  EXPECT_EQ(s.rooms, 2u);
  EXPECT_EQ(s.windows, 1u);
  EXPECT_NEAR(s.floor_area, 2 * 3.9 * 3.0, 1e-9);
  EXPECT_NEAR(s.wall_area, 8.4 * 3.4 - 2 * 3.9 * 3.0 - 0.2 * 0.9 - 0.2 * 1.0, 1e-9);
  std::map<std::string, int> names;
  std::map<model::Role, int> roles;
  for (const auto& p : m.polygons) {
    ++names[p.name];
    ++roles[p.role];
  }
  EXPECT_EQ(names["floor"], 2);
  EXPECT_EQ(names["ceiling"], 2);
  EXPECT_EQ(names["jamb"], 4);
  EXPECT_EQ(names["lintel"], 2);
  EXPECT_EQ(names["threshold"], 2);
  EXPECT_EQ(names["window 1"], 2);  // the panes; the reveals have names of their own
  EXPECT_EQ(names["reveal"] + names["sill"] + names["head"], 4);
  EXPECT_EQ(roles[model::Role::Opening], 4);  // a doorway on each face of its wall
  EXPECT_EQ(roles[model::Role::Glass], 2);
  for (const auto& p : m.polygons) {
    const Vec3 n = polygon_normal(p.vertices);
    if (p.name == "floor" || p.name == "threshold") {
      EXPECT_GT(n.z, 0.999);
    }
    if (p.name == "ceiling" || p.name == "lintel") {
      EXPECT_LT(n.z, -0.999);
    }
    if (p.name == "lintel") {
      EXPECT_NEAR(p.vertices[0].z, 2.0, 1e-12);
    }
    if (p.role == model::Role::Opening) {
      const double a = area(p);  // door width x door height: 0.9 m inner door, 1.0 m entrance
      EXPECT_TRUE(std::abs(a - 0.9 * 2.0) < 1e-9 || std::abs(a - 1.0 * 2.0) < 1e-9) << a;
      EXPECT_NEAR(std::abs(n.z), 0.0, 1e-12);
    }
  }
  // Wall faces look into the rooms: the middle wall's faces at x = 4.1 face -x, at x = 4.3 face +x.
  for (const auto& p : m.polygons) {
    if (p.name != "wall") continue;
    const Vec3 n = polygon_normal(p.vertices);
    if (std::abs(p.vertices[0].x - 4.1) < 1e-9 && std::abs(p.vertices[1].x - 4.1) < 1e-9) {
      EXPECT_LT(n.x, -0.999);
    }
    if (std::abs(p.vertices[0].x - 4.3) < 1e-9 && std::abs(p.vertices[1].x - 4.3) < 1e-9) {
      EXPECT_GT(n.x, 0.999);
    }
  }
  const model::Bounds b = bounds_of(m);
  EXPECT_NEAR(b.max.x, 8.4, 1e-12);
  EXPECT_NEAR(b.max.z, 2.5, 1e-12);
}

TEST(PlanBuilder, GapsOutsideTheDoorWidthsAreNotDoorways) {
  PlanOptions o;
  o.min_door_width = 0.95;  // the 0.9 m inner gap is now too narrow; the 1.0 m entrance still counts
  PlanStats s;
  (void)build_plan(two_rooms(), o, "plan.dxf", &s);
  EXPECT_EQ(s.doorways, 1u);
  EXPECT_EQ(s.rooms, 1u);  // the two rooms are one space through the open gap
}

TEST(PlanBuilder, OpenWiresAreCountedAndAPlanWithoutOutlinesIsAnError) {
  auto wires = two_rooms();
  wires.push_back({{10, 10, 0}, {11, 10, 0}, 0, 7});
  PlanStats s;
  (void)build_plan(wires, {}, "plan.dxf", &s);
  EXPECT_EQ(s.open_wires, 1u);
  try {
    (void)build_plan({{{0, 0, 0}, {1, 0, 0}, 0, 12}}, {}, "plan.dxf", nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("plan.dxf:12:"), std::string::npos) << e.what();
  }
}

}  // namespace test_plan_builder
}  // namespace walk::compiler
