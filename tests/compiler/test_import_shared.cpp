// Every shared model through the scene configs in config/scenes and import_model: counts of faces,
// openings, luminaires and circuits, and the bounding box in metres, each checked against numbers derived
// here from the files' text by a separate, simpler reading (line scans, OBJ "v"/"f" lines, .map key lines).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/import/import_model.hpp"
#include "compiler/scene/apply_rules.hpp"
#include "compiler/scene/scene_config.hpp"

namespace walk::compiler {
namespace test_import_shared {  // named, not anonymous: the suite compiles as unity batches

const std::string kData = WALK_SHARED_DATA;
const std::string kScenes = std::string(WALK_SOURCE_DIR) + "/config/scenes/";

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    out.push_back(line);
  }
  return out;
}

std::size_t count_role(const model::Model& m, model::Role role) {
  std::size_t n = 0;
  for (const auto& p : m.polygons) n += p.role == role ? 1 : 0;
  return n;
}

void expect_box(const model::Bounds& b, model::Vec3 lo, model::Vec3 hi, double tol) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(b.min[a], lo[a], tol) << "axis " << a;
    EXPECT_NEAR(b.max[a], hi[a], tol) << "axis " << a;
  }
}

// ---- EnergyPlus DXF: faces are 3DFACE lines; openings are faces whose 999 comment names a door or hole.
void check_energyplus(const std::string& scene, const std::string& dxf, std::size_t expected_faces) {
  const SceneConfig cfg = load_scene_config(kScenes + scene);
  ImportReport report;
  model::Model m = import_model(cfg, &report);
  const auto lines = lines_of(kData + dxf);
  std::size_t faces = 0, openings = 0, glass = 0;
  std::string comment;
  model::Bounds building;  // corners of faces on building layers (not "1", the north arrow, nor shading)
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i] == "999" && i + 1 < lines.size()) comment = lines[i + 1];
    if (lines[i] != "3DFACE") continue;
    ++faces;
    std::string layer;
    model::Vec3 corner[4];
    for (std::size_t k = i + 1; k + 1 < lines.size() && lines[k] != "  0" && lines[k] != "0"; k += 2) {
      const int code = std::atoi(lines[k].c_str());
      if (code == 8) layer = lines[k + 1];
      if (code >= 10 && code <= 33 && code % 10 <= 3)
        corner[code % 10][code / 10 - 1] = std::atof(lines[k + 1].c_str());
    }
    if (layer != "1" && layer != "Building Shading")
      for (const auto& c : corner) building.add(c);
    if (std::regex_search(comment, std::regex("_DOOR|_HOLE")))
      ++openings;
    else if (std::regex_search(comment, std::regex("_WIN")))
      ++glass;
  }
  EXPECT_EQ(faces, expected_faces);
  EXPECT_EQ(report.faces, faces);
  EXPECT_EQ(m.polygons.size(), faces);
  EXPECT_EQ(report.luminaires, 0u);
  EXPECT_EQ(report.circuits, 0u);
  (void)apply_rules(m, cfg);
  EXPECT_EQ(count_role(m, model::Role::Opening), openings);
  EXPECT_EQ(count_role(m, model::Role::Glass), glass);
  expect_box(bounds_of(m), building.min, building.max, 1e-12);
}

TEST(ImportShared, EnergyPlusHouse) {
  check_energyplus("house.toml", "/eplus-house-doors/house.dxf", 222);
}

TEST(ImportShared, EnergyPlusMediumOffice) {
  check_energyplus("medium-office.toml", "/eplus-medium-office/refbldg_medium_office.dxf", 146);
}

// ---- 2D plan: 94 LINEs on two closed outlines; wall footprint by the shoelace formula over the LINEs.
TEST(ImportShared, ApartmentPlan) {
  const auto lines = lines_of(kData + "/floorplan-2d-apartment/floorplan.dxf");
  std::size_t line_entities = 0;
  double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
  using P = std::pair<double, double>;
  std::multimap<P, P> next;  // both directions of every segment
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    if (lines[i] != "LINE" || lines[i - 1] != "  0") continue;
    ++line_entities;
    std::map<std::string, double> v;
    for (std::size_t k = i + 1; k + 1 < lines.size() && lines[k] != "  0"; k += 2)
      v[lines[k]] = std::atof(lines[k + 1].c_str());
    next.insert({{v[" 10"], v[" 20"]}, {v[" 11"], v[" 21"]}});
    next.insert({{v[" 11"], v[" 21"]}, {v[" 10"], v[" 20"]}});
    xmin = std::min({xmin, v[" 10"], v[" 11"]});
    xmax = std::max({xmax, v[" 10"], v[" 11"]});
    ymin = std::min({ymin, v[" 20"], v[" 21"]});
    ymax = std::max({ymax, v[" 20"], v[" 21"]});
  }
  // Walk each closed outline (every endpoint joins exactly two LINEs) and add up |shoelace| areas.
  double footprint = 0.0;
  std::set<P> seen;
  for (const auto& [start, ignored] : next) {
    if (seen.count(start)) continue;
    P prev = start, cur = start;
    double twice = 0.0;
    do {
      seen.insert(cur);
      auto range = next.equal_range(cur);
      P to = range.first->second;
      if (to == prev && std::next(range.first) != range.second) to = std::next(range.first)->second;
      twice += cur.first * to.second - to.first * cur.second;
      prev = cur;
      cur = to;
    } while (cur != start);
    footprint += std::abs(twice) / 2;
  }
  ASSERT_EQ(line_entities, 94u);
  const double in = 0.0254;
  const SceneConfig cfg = load_scene_config(kScenes + "apartment-plan.toml");
  ImportReport report;
  const model::Model m = import_model(cfg, &report);
  EXPECT_NE(report.detail.find("LINE 94"), std::string::npos) << report.detail;
  EXPECT_NE(report.detail.find("($INSUNITS 1)"), std::string::npos) << report.detail;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(report.detail, match, std::regex("wall footprint ([0-9.]+) m2")));
  EXPECT_NEAR(std::stod(match[1]), footprint * in * in, 0.01);  // printed to 0.01 m2
  // Counted on a drawing of the plan (docs/IMPORT.md): 11 gaps between facing wall ends (two of them either
  // side of a 6-inch chase) close 8 rooms; each doorway has an opening on both faces of its wall.
  EXPECT_NE(report.detail.find("doorways 11 rooms 8 windows 8 (unplaced 0)"), std::string::npos)
      << report.detail;
  EXPECT_EQ(report.openings, 22u);
  EXPECT_EQ(count_role(m, model::Role::Glass), 16u);  // 8 windows, a pane on each face
  EXPECT_EQ(report.luminaires, 0u);
  expect_box(bounds_of(m), {xmin * in, ymin * in, 0.0}, {xmax * in, ymax * in, 2.6}, 1e-9);
}

// ---- Quake maps: a line-based reading of entities, brushes and plane lines.
struct MapFacts {
  std::size_t planes = 0, planes_drawn = 0, lights = 0, door_planes = 0;
  std::set<std::string> circuits;
  model::Bounds axial;   // union of the boxes of all-axial, drawn brushes: exact brush extents
  model::Bounds points;  // box of the plane points of drawn brushes (editors put them on brush corners)
};

MapFacts scan_map(const std::string& path) {
  MapFacts f;
  int depth = 0;
  std::map<std::string, std::string> keys;
  std::vector<std::vector<std::string>> brushes;  // plane lines of the current entity
  const auto finish_entity = [&] {
    const std::string cls = keys["classname"];
    if (cls.rfind("light", 0) == 0) {
      ++f.lights;
      const std::string tn = keys["targetname"];
      const int style = std::atoi(keys["style"].c_str());
      f.circuits.insert(!tn.empty() ? "switch " + tn : style ? "style " + std::to_string(style) : "static");
    }
    const bool trigger = cls.rfind("trigger_", 0) == 0;
    for (const auto& b : brushes) {
      f.planes += b.size();
      bool all_clip = true, axial = true;
      model::Bounds box;
      for (const auto& line : b) {
        std::istringstream in(line);
        std::string tok, tex;
        double p[3][3];
        for (auto& point : p) in >> tok >> point[0] >> point[1] >> point[2] >> tok;
        in >> tex;
        for (auto& c : tex) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        all_clip = all_clip && tex == "clip";
        // An axial plane has one coordinate equal in all three points.
        int same = -1;
        for (int a = 0; a < 3; ++a)
          if (p[0][a] == p[1][a] && p[1][a] == p[2][a]) same = a;
        if (same < 0)
          axial = false;
        else {
          model::Vec3 v(0.0);
          v[same] = p[0][same];
          box.add(v);  // only the constrained coordinate matters below
        }
      }
      if (trigger || all_clip) continue;
      f.planes_drawn += b.size();
      for (const auto& line : b) {
        std::istringstream in(line);
        std::string tok;
        for (int k = 0; k < 3; ++k) {
          model::Vec3 p;
          in >> tok >> p.x >> p.y >> p.z >> tok;
          f.points.add(p);
        }
      }
      if (cls == "func_door" || cls == "func_door_secret") f.door_planes += b.size();
      (void)box;
      if (axial && b.size() == 6) {
        // The box of an axial 6-plane brush: min and max of each axis' two plane constants.
        model::Bounds exact;
        double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
        for (const auto& line : b) {
          std::istringstream in(line);
          std::string tok;
          double p[3][3];
          for (auto& point : p) in >> tok >> point[0] >> point[1] >> point[2] >> tok;
          for (int a = 0; a < 3; ++a)
            if (p[0][a] == p[1][a] && p[1][a] == p[2][a]) {
              lo[a] = std::min(lo[a], p[0][a]);
              hi[a] = std::max(hi[a], p[0][a]);
            }
        }
        f.axial.add({lo[0], lo[1], lo[2]});
        f.axial.add({hi[0], hi[1], hi[2]});
      }
    }
  };
  for (const auto& line : lines_of(path)) {
    if (line == "{") {
      if (depth == 0) {
        keys.clear();
        brushes.clear();
      } else {
        brushes.emplace_back();
      }
      ++depth;
    } else if (line == "}") {
      if (--depth == 0) finish_entity();
    } else if (depth == 1 && !line.empty() && line[0] == '"') {
      const auto q = line.find('"', 1);
      keys[line.substr(1, q - 1)] =
          line.substr(line.find('"', q + 1) + 1, line.rfind('"') - line.find('"', q + 1) - 1);
    } else if (depth == 2 && !line.empty() && line[0] == '(') {
      brushes.back().push_back(line);
    }
  }
  return f;
}

void check_map(const std::string& scene, const std::string& file, std::size_t planes, std::size_t lights) {
  const MapFacts facts = scan_map(kData + file);
  EXPECT_EQ(facts.planes, planes);  // SOURCE.txt's brush face count
  EXPECT_EQ(facts.lights, lights);  // and light entities
  const SceneConfig cfg = load_scene_config(kScenes + scene);
  ImportReport report;
  const model::Model m = import_model(cfg, &report);
  std::smatch match;
  ASSERT_TRUE(std::regex_search(report.detail, match, std::regex("csg faces ([0-9]+) hidden")));
  EXPECT_EQ(std::stoul(match[1]), facts.planes_drawn) << report.detail;  // every drawn plane made one face
  EXPECT_EQ(report.luminaires, facts.lights);
  EXPECT_EQ(report.circuits, facts.circuits.size());
  std::set<std::string> names;
  for (const auto& c : m.circuits) names.insert(c.name);
  EXPECT_EQ(names, facts.circuits);
  EXPECT_GT(report.openings, 0u);
  EXPECT_LE(report.openings, facts.door_planes * 4);  // door faces, some split by CSG among door brushes
  // The level's box contains every axial brush's exact box and lies within the plane points' box.
  const model::Bounds b = bounds_of(m);
  const double u = 0.0254;
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(b.min[a], facts.axial.min[a] * u + 1e-9);
    EXPECT_GE(b.max[a], facts.axial.max[a] * u - 1e-9);
    EXPECT_GE(b.min[a], facts.points.min[a] * u - 1e-9);
    EXPECT_LE(b.max[a], facts.points.max[a] * u + 1e-9);
  }
}

TEST(ImportShared, QuakeE1m1) {
  check_map("quake-e1m1.toml", "/quake-maps/e1m1.map", 7523, 198);
}

TEST(ImportShared, QuakeDm1) {
  check_map("quake-dm1.toml", "/quake-maps/dm1.map", 3080, 88);
}

// ---- Meshes: faces are "f" lines; the box is the "v" lines' box, y-up turned to z-up and scaled.
void check_obj(const std::string& scene, const std::string& file, double scale, std::size_t luminaires) {
  std::size_t faces = 0;
  model::Bounds box;
  for (const auto& line : lines_of(kData + file)) {
    if (line.rfind("f ", 0) == 0) ++faces;
    if (line.rfind("v ", 0) == 0) {
      std::istringstream in(line.substr(2));
      double x, y, z;
      in >> x >> y >> z;
      box.add(model::Vec3(x, -z, y) * scale);
    }
  }
  const SceneConfig cfg = load_scene_config(kScenes + scene);
  ImportReport report;
  const model::Model m = import_model(cfg, &report);
  EXPECT_EQ(report.faces, faces);
  EXPECT_EQ(report.openings, 0u);
  EXPECT_EQ(report.luminaires, luminaires);
  EXPECT_EQ(report.circuits, luminaires ? 1u : 0u);
  expect_box(bounds_of(m), box.min, box.max, 1e-6 * glm::length(box.size()));  // float vertices in assimp
}

TEST(ImportShared, CornellBoxObj) {
  check_obj("cornell-box-obj.toml", "/cornell-box/CornellBox-Original.obj", 1.0, 1);
  const model::Model m = import_model(load_scene_config(kScenes + "cornell-box-obj.toml"), nullptr);
  ASSERT_EQ(m.luminaires.size(), 1u);
  const auto& l = m.luminaires[0];
  EXPECT_NEAR(l.normal.z, -1.0, 1e-6);  // the lamp faces down
  // mtl: Ke 17 12 4; the lamp quad is 0.47 x 0.38 units (from its four "v" lines): power = pi Ke A.
  EXPECT_NEAR(l.width * l.height, 0.47 * 0.38, 0.01);
  EXPECT_NEAR(l.power.r / l.power.b, 17.0 / 4.0, 1e-6);
  EXPECT_NEAR(l.power.r, std::acos(-1.0) * 17.0 * l.width * l.height, 1e-6);
}

TEST(ImportShared, ConferenceRoomObj) {
  check_obj("conference-room.toml", "/conference-room/conference.obj", 0.003, 0);
}

TEST(ImportShared, SibenikObj) {
  check_obj("sibenik.toml", "/sibenik/sibenik.obj", 1.0, 0);
}

}  // namespace test_import_shared
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_import_shared {  // named, not anonymous: the suite compiles as unity batches

// No shipped scene has a stray face or an absurd coordinate: the stray fence leaves every real model whole.
TEST(ImportShared, NoShippedSceneHasStrays) {
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".toml") continue;
    const SceneConfig cfg = load_scene_config(entry.path().string());
    model::Model m = import_model(cfg, nullptr);
    EXPECT_NO_THROW(check_coordinates(m, cfg.model_file)) << entry.path();
    (void)apply_rules(m, cfg);
    const StrayStats s = remove_strays(m, true);
    EXPECT_EQ(s.faces, 0u) << entry.path() << ": " << s.summary();
  }
}

}  // namespace test_import_shared
}  // namespace walk::compiler
