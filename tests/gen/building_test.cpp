// `walk gen building`: a small instance's counts, furniture clear of every wall and of each other, the open
// stair and lift shaft present, and the same seed giving the same bytes.
#include "tools/gen/building.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.hpp"
#include "tools/gen/furniture.hpp"
#include "tools/gen/plan_unit.hpp"
#include "tools/gen/scene_writer.hpp"

namespace walk::gen {
namespace building_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

const std::string kData = WALK_SHARED_DATA;
const std::string kScenes = std::string(WALK_SOURCE_DIR) + "/config/scenes";

// Shared by the tests: importing the plan and cutting the conference room take about a second.
struct Parts {
  PlanUnit plan = load_plan_unit("apartment", kScenes, kData);
  FurnitureCatalogue furniture = cut_furniture(kData + "/conference-room/conference.obj", 0.003);
};
const Parts& parts() {
  static const Parts p;
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Does the segment a-b (seen from above) pass through the open box lo..hi? Written apart from the
// generator's own test so that the check does not share its mistakes.
bool crosses_box(glm::dvec2 a, glm::dvec2 b, glm::dvec2 lo, glm::dvec2 hi) {
  constexpr int kSteps = 400;  // 1/400 of a wall: finer than any gap between an object and a wall
  for (int i = 0; i <= kSteps; ++i) {
    const glm::dvec2 p = a + (b - a) * (double(i) / kSteps);
    if (p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y) return true;
  }
  return false;
}

TEST(FurnitureCut, FindsSeparateChairsAndKeepsTheirMaterials) {
  const auto& cat = parts().furniture;
  // Standing on the floor: 12 chairs, two bins, a cabinet and the table (its top joined to the four
  // pedestals under it); the chairs are one shape turned by a few degrees each.
  EXPECT_EQ(cat.standing, 16u);
  EXPECT_EQ(cat.objects.size(), 4u);
  EXPECT_TRUE(std::any_of(cat.objects.begin(), cat.objects.end(), [](const FurnitureObject& o) {
    return o.size.x > 2.5 && o.size.y > 0.8 && o.size.z > 0.5;  // the 2.64 x 0.88 m table, standing
  }));
  for (const auto& o : cat.objects) {
    EXPECT_GT(o.triangles, 0u) << o.name;
    EXPECT_LE(std::max(o.size.x, o.size.y), 3.0) << o.name << ": larger than the furniture limit";
    double zmin = 1e9;
    for (const auto& v : o.vertices) zmin = std::min(zmin, v.z);
    EXPECT_NEAR(zmin, 0.0, 1e-9) << o.name << " stands on z = 0";
    std::vector<std::uint32_t> mats;
    for (const auto& f : o.faces) mats.push_back(f.material);
    std::sort(mats.begin(), mats.end());
    EXPECT_LT(mats.back(), cat.materials.size());
  }
  // A chair is made of several materials (frame, seat): materials are kept per face, not per object.
  EXPECT_TRUE(std::any_of(cat.objects.begin(), cat.objects.end(), [](const FurnitureObject& o) {
    return std::any_of(o.faces.begin(), o.faces.end(),
                       [&](const auto& f) { return f.material != o.faces.front().material; });
  }));
}

TEST(GenBuilding, SmallInstanceCounts) {
  BuildingOptions o;
  o.storeys = 3;
  o.furnish = 0.15;
  o.seed = 7;
  const Building b = compose_building(parts().plan, parts().furniture, o);
  EXPECT_EQ(b.storeys, 3);
  // Per storey: the plan's 8 rooms in each of two units, and the corridor.
  EXPECT_EQ(b.rooms.size(), 3u * 17u);
  std::size_t triangles = 0, stair_faces = 0, holes = 0, lift_doors = 0;
  for (const auto& p : b.parts) {
    for (const auto& f : p.faces) triangles += f.size() - 2;
    if (p.group.find("stair") != std::string::npos) {
      stair_faces += p.faces.size();
      if (p.material == "opening") holes += p.faces.size();
    }
    if (p.group.find("lift door") != std::string::npos && p.material == "opening")
      lift_doors += p.faces.size();
  }
  EXPECT_EQ(triangles, b.triangles);
  // Two flights (storeys 1-2 and 2-3), each through a hole cut from both sides of the slab above it.
  EXPECT_EQ(holes, 2u * 2u);
  EXPECT_GT(stair_faces, 2u * 20u);
  EXPECT_EQ(lift_doors, 3u * 2u);
  // 0.15 objects per square metre of the rooms' floor (2 x 82 m2 a storey), give or take rounding.
  double area = 0.0;
  for (const auto& r : b.rooms)
    if (r.name.find("corridor") == std::string::npos) area += r.area;
  EXPECT_NEAR(b.objects.size(), 0.15 * area, 3.0);
  std::size_t furniture_triangles = 0;
  for (const auto& obj : b.objects) furniture_triangles += obj.triangles;
  EXPECT_EQ(furniture_triangles + b.structure_triangles, b.triangles);
  for (const auto& r : b.rooms) EXPECT_FALSE(r.panels.empty()) << r.name << " has no ceiling panel";
}

TEST(GenBuilding, FurnitureStandsOnFloorsClearOfWallsAndEachOther) {
  BuildingOptions o;
  o.storeys = 2;
  o.furnish = 0.18;
  o.seed = 3;
  const Building b = compose_building(parts().plan, parts().furniture, o);
  ASSERT_GT(b.objects.size(), 40u);
  const double H = parts().plan.storey_height;
  for (const auto& obj : b.objects) {
    const double floor_z = std::round(obj.box.min.z / H) * H;
    EXPECT_NEAR(obj.box.min.z, floor_z, 1e-6) << obj.room << " object floats or sinks";
    const glm::dvec2 lo(obj.box.min), hi(obj.box.max);
    for (const auto& w : b.walls) {
      double zlo = 1e9, zhi = -1e9;
      glm::dvec2 a(1e9), c(-1e9);
      for (const auto& v : w.vertices) zlo = std::min(zlo, v.z), zhi = std::max(zhi, v.z);
      if (zhi <= obj.box.min.z || zlo >= obj.box.max.z) continue;  // another storey
      // A vertical face seen from above is a segment: its two extreme corners.
      std::vector<glm::dvec2> xy;
      for (const auto& v : w.vertices) xy.emplace_back(v);
      auto ends = std::minmax_element(xy.begin(), xy.end(),
                                      [](auto p, auto q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
      a = *ends.first, c = *ends.second;
      EXPECT_FALSE(crosses_box(a, c, lo, hi))
          << obj.room << " object at " << lo.x << "," << lo.y << " crosses wall " << w.name;
    }
  }
  for (std::size_t i = 0; i < b.objects.size(); ++i)
    for (std::size_t j = i + 1; j < b.objects.size(); ++j) {
      const auto& p = b.objects[i].box;
      const auto& q = b.objects[j].box;
      const bool overlap = p.min.x < q.max.x && q.min.x < p.max.x && p.min.y < q.max.y && q.min.y < p.max.y &&
                           p.min.z < q.max.z && q.min.z < p.max.z;
      EXPECT_FALSE(overlap) << "objects " << i << " and " << j << " in " << b.objects[i].room;
    }
}

TEST(GenBuilding, SameSeedSameBytesOtherSeedOtherBuilding) {
  BuildingOptions o;
  o.storeys = 2;
  o.furnish = 0.2;
  const fs::path dir = fs::temp_directory_path() / ("walk_gen_test_" + std::to_string(::getpid()));
  auto write = [&](std::uint64_t seed, const std::string& name) {
    o.seed = seed;
    const Building b = compose_building(parts().plan, parts().furniture, o);
    return write_building_scene((dir / name).string(), b, parts().plan, parts().furniture, "test");
  };
  write(5, "a");
  write(5, "b");
  write(6, "c");
  for (const char* f : {"building.obj", "building.mtl", "scene.toml", "kiosk.toml"}) {
    const std::string a = slurp(dir / "a" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_EQ(a, slurp(dir / "b" / f)) << f << " differs for the same seed";
  }
  EXPECT_NE(slurp(dir / "a" / "building.obj"), slurp(dir / "c" / "building.obj"));
  // No temporary file is left next to the scene.
  for (const auto& e : fs::directory_iterator(dir / "a")) EXPECT_NE(e.path().filename().string()[0], '.');
  fs::remove_all(dir);
}

TEST(GenBuilding, BadOptionsAreErrors) {
  BuildingOptions o;
  o.storeys = 0;
  EXPECT_THROW((void)compose_building(parts().plan, parts().furniture, o), walk::Error);
  o.storeys = 1;
  o.furnish = 5.0;  // five chairs or tables on every square metre
  try {
    (void)compose_building(parts().plan, parts().furniture, o);
    FAIL() << "a density that cannot fit was accepted";
  } catch (const walk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("--furnish"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)load_plan_unit("castle", kScenes, kData), walk::Error);
}

}  // namespace building_test
}  // namespace walk::gen
