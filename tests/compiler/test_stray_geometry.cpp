// Hard inputs stay bounded: non-finite and absurd coordinates are errors naming file and line, faces far
// from the rest are left out before they can set the weld tolerance or the mesh, a compile with nothing left
// to draw writes nothing, and knobs that multiply work are refused before the work.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/import/mesh_reader.hpp"
#include "compiler/pipeline.hpp"
#include "compiler/scene/work_budget.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_stray_geometry {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;
using model::Vec3;

model::Polygon square(const Vec3& at, double side, std::uint32_t line) {
  model::Polygon p;
  p.vertices = {at, at + Vec3(side, 0, 0), at + Vec3(side, side, 0), at + Vec3(0, side, 0)};
  p.source_line = line;
  return p;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(StrayGeometry, NonFiniteAndAbsurdCoordinatesNameFileAndLine) {
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           1e20, -2 * kMaxCoordinate}) {
    model::Model m;
    m.polygons = {square({0, 0, 0}, 1, 3), square({0, 0, 1}, 1, 7)};
    m.polygons[1].vertices[2].y = bad;
    const std::string err = error_of([&] { check_coordinates(m, "plan.dxf"); });
    EXPECT_NE(err.find("plan.dxf:7"), std::string::npos) << bad << ": " << err;
  }
  model::Model national_grid;  // a real site in national grid coordinates is fine
  national_grid.polygons = {square({4.5e6, 5.2e6, 120.0}, 10, 1)};
  EXPECT_NO_THROW(check_coordinates(national_grid, "site.dxf"));
  model::Model hole;  // holes are checked too
  hole.polygons = {square({0, 0, 0}, 4, 2)};
  hole.polygons[0].holes = {{{1, 1, 0}, {1, std::nan(""), 0}, {2, 2, 0}}};
  EXPECT_NE(error_of([&] { check_coordinates(hole, "h.obj"); }).find("h.obj:2"), std::string::npos);
}

TEST(StrayGeometry, OneFaceFarAwayIsLeftOutUnlessKept) {
  model::Model m;
  for (int i = 0; i < 40; ++i) m.polygons.push_back(square({double(i % 8), double(i / 8), 0.0}, 1, i + 1));
  m.polygons.push_back(square({1.0e6, 0, 0}, 1, 99));   // 1,000 km east
  m.polygons.push_back(square({0, 5.0e3, 0}, 1, 100));  // 5 km north
  model::Model kept = m;
  const StrayStats s = remove_strays(m, false);
  EXPECT_EQ(s.faces, 2u);
  EXPECT_EQ(s.first_line, 99u);
  EXPECT_NEAR(s.first.x, 1.0e6 + 0.5, 1e-6);
  EXPECT_EQ(m.polygons.size(), 40u);
  EXPECT_LT(model::bounds_of(m).size().x, 10.0) << "what is left is the building";
  EXPECT_EQ(remove_strays(kept, true).faces, 2u);
  EXPECT_EQ(kept.polygons.size(), 42u) << "kept when the scene says so";
}

TEST(StrayGeometry, RealSpreadsAreNotStrays) {
  // A 2 km campus of evenly spread buildings, a tall tower crowding its faces into few storeys, and a
  // model of three faces: none is cut.
  model::Model campus;
  for (int i = 0; i < 200; ++i) campus.polygons.push_back(square({10.0 * i, 5.0 * (i % 7), 0.0}, 5, i + 1));
  EXPECT_EQ(remove_strays(campus, false).faces, 0u);
  model::Model tower;
  for (int i = 0; i < 1000; ++i) tower.polygons.push_back(square({0, 0, i < 995 ? 0.01 * i : 300.0}, 5, 1));
  EXPECT_EQ(remove_strays(tower, false).faces, 0u) << "the roof 300 m over a furnished lobby is kept";
  model::Model few;
  few.polygons = {square({0, 0, 0}, 1, 1), square({50, 0, 0}, 1, 2), square({0, 80, 0}, 1, 3)};
  EXPECT_EQ(remove_strays(few, false).faces, 0u);
  model::Model none;
  EXPECT_EQ(remove_strays(none, false).faces, 0u);
}

class HardCompile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_hard_compile_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A closed 4 x 4 x 3 m room (faces inward, z up) with a lamp, plus `extra` OBJ lines.
  std::string scene(const std::string& extra_obj, const std::string& extra_toml = {}) {
    std::ofstream(dir_ / "room.mtl") << "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";
    std::ofstream(dir_ / "room.obj")
        << "mtllib room.mtl\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 3\nv 4 0 3\nv 4 4 3\nv 0 4 3\n"
        << "v 1.5 1.5 2.95\nv 1.5 2.5 2.95\nv 2.5 2.5 2.95\nv 2.5 1.5 2.95\n"
        << "usemtl wall\nf 1 2 3 4\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\nf 5 8 7 6\n"
        << "usemtl lamp\nf 9 10 11 12\n"
        << extra_obj;
    const fs::path path = dir_ / "scene.toml";
    std::ofstream(path) << "[model]\nfile = \"room.obj\"\nunits = \"m\"\nup = \"z\"\n"
                        << extra_toml << "[lighting]\ngrid = 0.5\nrays_per_watt = 100\n";
    return path.string();
  }
  fs::path dir_;
};

TEST_F(HardCompile, StrayFaceThousandKilometresAwayNeitherInflatesTheWeldNorTheMesh) {
  const auto plain = compile_scene(load_scene_config(scene({})));
  const auto r = compile_scene(
      load_scene_config(scene("usemtl wall\nv 1000000 0 0\nv 1000001 0 0\nv 1000001 1 0\nf 13 14 15\n")));
  EXPECT_EQ(r.bundle.vertices.size(), plain.bundle.vertices.size()) << "the stray face is left out";
  for (const auto& s : r.stages)
    if (s.name == "cleanup") {
      EXPECT_NE(s.detail.find("strays 1"), std::string::npos) << s.detail;
      EXPECT_NE(s.detail.find("weld 0.0000"), std::string::npos) << "weld stays sub-millimetre: " << s.detail;
    }
  // Kept on request: drawn like any face.
  const auto kept = compile_scene(load_scene_config(scene(
      "usemtl wall\nv 1000000 0 0\nv 1000001 0 0\nv 1000001 1 0\nf 13 14 15\n", "outliers = \"keep\"\n")));
  EXPECT_EQ(kept.bundle.polygons.size(), plain.bundle.polygons.size() + 1);
}

TEST_F(HardCompile, HugeCoordinateIsAnErrorNamingTheFile) {
  const std::string err =
      error_of([&] { (void)compile_scene(load_scene_config(scene("v 1e20 0 0\nf 1 2 13\n"))); });
  EXPECT_NE(err.find("room.obj"), std::string::npos) << err;
  EXPECT_NE(err.find("from the origin"), std::string::npos) << err;
}

TEST_F(HardCompile, WorkMultipliersAreRefusedBeforeTheWork) {
  const SceneConfig config = load_scene_config(scene({}));
  SceneConfig rays = config;
  rays.lighting.rays_per_watt = 1e9;
  const auto start = std::chrono::steady_clock::now();
  const std::string err = error_of([&] { (void)compile_scene(rays); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0)
      << "refused before casting (a generous bound for a loaded CI machine; it takes milliseconds)";
  EXPECT_NE(err.find("rays_per_watt"), std::string::npos) << err;
  EXPECT_NE(err.find("2e+09"), std::string::npos) << "the limit is named: " << err;
  // Patches by grid and area against the machine's memory: the two 4 m squares at 1 cm are 320,000 patches,
  // far too many for a 64 MiB machine, and fine for this one at 0.5 m.
  model::Model room;
  room.polygons = {square({0, 0, 0}, 4, 1), square({0, 0, 3}, 4, 2)};
  SceneConfig fine = config;
  fine.lighting.grid = 0.01;
  EXPECT_NEAR(estimated_patches(room, 0.01), 2 * 160000.0, 1.0);
  const std::string patches = error_of([&] { check_patch_budget(room, fine, 64ull << 20); });
  EXPECT_NE(patches.find("[lighting] grid = 0.01"), std::string::npos) << patches;
  EXPECT_NE(patches.find("raise grid to at least"), std::string::npos) << patches;
  EXPECT_NO_THROW(check_patch_budget(room, config, 64ull << 20));
  // Light is sparse, so a building of many circuits is not charged for each at every patch: 12,800 patches
  // (grid 5 cm) with 1,000 circuits fit a 128 MiB machine (charged all, they would need 1.2 GB), and
  // 80,000 (2 cm) do not.
  room.circuits.resize(1000);
  SceneConfig many = config;
  many.lighting.grid = 0.05;
  EXPECT_NO_THROW(check_patch_budget(room, many, 128ull << 20));
  many.lighting.grid = 0.02;
  EXPECT_NE(error_of([&] { check_patch_budget(room, many, 128ull << 20); }).find("[lighting] grid = 0.02"),
            std::string::npos);
  // The sampled PVS's rays, once the cells are known and before any is cast.
  SceneConfig sampled = config;
  sampled.visibility.sample_points = 1'000'000;
  sampled.visibility.rays_per_point = 1'000'000;
  const auto cells_start = std::chrono::steady_clock::now();
  const std::string cells = error_of([&] { (void)compile_scene(sampled); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - cells_start).count(), 30.0)
      << "refused before sampling (a generous bound; the light stage before it takes most of this)";
  EXPECT_NE(cells.find("[visibility] sample_points = 1000000 x rays_per_point = 1000000"), std::string::npos)
      << cells;
  EXPECT_NE(cells.find("scene.toml"), std::string::npos) << "names the scene file: " << cells;
  EXPECT_NE(cells.find("2e+09"), std::string::npos) << cells;
}

TEST_F(HardCompile, NothingLeftToDrawIsAnErrorAndNothingIsWritten) {
  // Every face is degenerate (its corners collinear): clean-up drops them all.
  const fs::path path = dir_ / "scene.toml";
  std::ofstream(dir_ / "flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n";
  std::ofstream(path) << "[model]\nfile = \"flat.obj\"\nunits = \"m\"\nup = \"z\"\n";
  const std::string out = (dir_ / "flat.walk").string();
  const std::string err = error_of([&] { (void)compile_to_file(path.string(), out, true); });
  EXPECT_NE(err.find("no face is left to draw"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(HardCompile, MissingMaterialLibraryIsWarnedAboutByName) {
  std::ofstream(dir_ / "grey.obj") << "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  MeshStats stats;
  (void)read_mesh((dir_ / "grey.obj").string(), {1.0, false, 1.0, {}}, &stats);
  EXPECT_EQ(stats.material_libraries_missing, 1u);
  std::ofstream(dir_ / "ok.mtl") << "newmtl a\nKd 1 0 0\n";
  std::ofstream(dir_ / "red.obj") << "mtllib ok.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  (void)read_mesh((dir_ / "red.obj").string(), {1.0, false, 1.0, {}}, &stats);
  EXPECT_EQ(stats.material_libraries_missing, 0u);
  // The model names its own fallback (<model>.mtl) and it is missing: one warning, not two.
  std::ofstream(dir_ / "self.obj") << "mtllib self.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  (void)read_mesh((dir_ / "self.obj").string(), {1.0, false, 1.0, {}}, &stats);
  EXPECT_EQ(stats.material_libraries_missing, 1u);
  // The named library is missing but assimp's fallback beside the model is there: still warned, and the
  // fallback's material is the one used.
  std::ofstream(dir_ / "blue.mtl") << "newmtl a\nKd 0 0 1\n";
  std::ofstream(dir_ / "blue.obj") << "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  const model::Model blue = read_mesh((dir_ / "blue.obj").string(), {1.0, false, 1.0, {}}, &stats);
  EXPECT_EQ(stats.material_libraries_missing, 1u);
  ASSERT_FALSE(blue.polygons.empty());
  EXPECT_DOUBLE_EQ(blue.materials.at(blue.polygons.front().material).reflectance.b, 1.0);
}

TEST_F(HardCompile, ModelPathThatIsAFolderSaysSo) {
  fs::create_directories(dir_ / "building.obj");
  std::ofstream(dir_ / "scene.toml") << "[model]\nfile = \"building.obj\"\n";
  const std::string err = error_of([&] { (void)load_scene_config((dir_ / "scene.toml").string()); });
  EXPECT_NE(err.find("is a folder"), std::string::npos) << err;
  EXPECT_NE(err.find("file"), std::string::npos) << err;
}

}  // namespace test_stray_geometry
}  // namespace walk::compiler
