// walk export radiance: the bundle as a Radiance scene whose syntax holds (every primitive's three argument
// lists have the counts they announce), whose counts match the bundle, and whose lights carry the solver's
// power in world metres.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "compiler/export/radiance_export.hpp"
#include "compiler/lighting/drawn_triangles.hpp"
#include "compiler/pipeline.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_radiance_export {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

struct Primitive {
  std::string modifier, type, name;
  std::vector<double> reals;
};

// Radiance's scene grammar: `modifier type name`, then n strings, n integers and n reals, each list led by
// its count. Fails the test on a short list or a number that is not one.
std::vector<Primitive> parse(const std::string& text) {
  std::istringstream lines(text);
  std::string line, body;
  while (std::getline(lines, line))
    if (line.empty() || line[0] != '#') body += line + "\n";
  std::istringstream in(body);
  std::vector<Primitive> out;
  Primitive p;
  while (in >> p.modifier >> p.type >> p.name) {
    std::size_t n = 0;
    std::string token;
    EXPECT_TRUE(in >> n) << p.name;
    for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(in >> token) << p.name;
    EXPECT_TRUE(in >> n) << p.name;
    for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(in >> token) << p.name;
    EXPECT_TRUE(in >> n) << p.name;
    p.reals.assign(n, 0.0);
    for (auto& r : p.reals) {
      EXPECT_TRUE(in >> r) << p.name;
      EXPECT_TRUE(std::isfinite(r)) << p.name;
    }
    out.push_back(p);
  }
  EXPECT_TRUE(in.eof()) << "trailing text";
  return out;
}

TEST(RadianceExport, SceneHasItsTrianglesMaterialsAndLightsAtTheSolversPower) {
  const fs::path dir = fs::temp_directory_path() / ("walk_radiance_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A 4 m room, faces turned inwards, 10 m east of the origin (so world and local coordinates differ), a
  // 1 x 0.5 m panel under its ceiling and an isotropic fixture in its middle.
  std::ofstream(dir / "room.obj") << "v 10 0 0\nv 14 0 0\nv 14 4 0\nv 10 4 0\nv 10 0 4\nv 14 0 4\nv 14 4 4\n"
                                     "v 10 4 4\nf 1 2 3 4\nf 5 8 7 6\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\n"
                                     "f 4 3 7 8\n";
  std::ofstream(dir / "iso.ies") << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n"
                                    "100 100 100\n";
  std::ofstream(dir / "room.toml")
      << "[model]\nfile = \"room.obj\"\nup = \"z\"\n"
         "[[luminaires.panel]]\nposition = [12, 2, 3.9]\nsize = [1.0, 0.5]\n"
         "power = 60\n"
         "[[luminaires.fixture]]\nposition = [12, 2, 2]\nphotometry = \"iso.ies\"\n"
         "flux = 1000\n"
         "[lighting]\ngrid = 1.0\ntarget_error = 0.2\n";
  ASSERT_TRUE(compile_to_file((dir / "room.toml").string(), (dir / "room.walk").string(), true));
  const auto bundle = model::Bundle::open((dir / "room.walk").string());
  const auto stats = export_radiance(*bundle, (dir / "rad").string());
  EXPECT_FALSE(fs::exists(dir / "rad" / "scene.rad.part"));
  std::ifstream file(dir / "rad" / "scene.rad");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto primitives = parse(text);
  std::map<std::string, int> count;
  for (const auto& p : primitives) ++count[p.type];
  EXPECT_EQ(count["polygon"], int(drawn_triangles(*bundle).size()) + 1);  // the walls, and the panel
  EXPECT_EQ(stats.polygons, drawn_triangles(*bundle).size());
  EXPECT_EQ(count["plastic"], 1);
  EXPECT_EQ(count["light"], 2);
  EXPECT_EQ(count["sphere"], 1);
  EXPECT_EQ(stats.fixtures_approximated, 1u);
  for (const auto& p : primitives) {
    if (p.type == "polygon") {
      ASSERT_EQ(p.reals.size() % 3, 0u) << p.name;
      for (std::size_t i = 0; i < p.reals.size(); i += 3) {  // world metres: inside the room's box
        EXPECT_GE(p.reals[i], 10.0 - 1e-5) << p.name;
        EXPECT_LE(p.reals[i], 14.0 + 1e-5) << p.name;
      }
    }
    if (p.name == "panel_0") {
      ASSERT_EQ(p.reals.size(), 12u);
      for (std::size_t i = 0; i < 12; i += 3) {
        EXPECT_NEAR(std::abs(p.reals[i] - 12.0), 0.5, 1e-6);
        EXPECT_NEAR(std::abs(p.reals[i + 1] - 2.0), 0.25, 1e-6);
        EXPECT_NEAR(p.reals[i + 2], 3.9, 1e-6);
      }
      // Counter-clockwise about the panel's normal (down): the first edges' cross product points down.
      const double ux = p.reals[3] - p.reals[0], uy = p.reals[4] - p.reals[1];
      const double vx = p.reals[6] - p.reals[3], vy = p.reals[7] - p.reals[4];
      EXPECT_LT(ux * vy - uy * vx, 0.0);
    }
    if (p.type == "light" && p.name == "lamp_0") {  // the panel: radiance = exitance / pi
      ASSERT_EQ(p.reals.size(), 3u);
      EXPECT_NEAR(p.reals[1], 60.0 / (std::numbers::pi * 0.5), 1e-5);
    }
    if (p.type == "light" && p.name == "lamp_1") {  // the fixture: power / (4 pi^2 r^2), r = 2 cm
      ASSERT_EQ(p.reals.size(), 3u);
      EXPECT_NEAR(p.reals[1], 1000.0 / 179.0 / (4.0 * std::numbers::pi * std::numbers::pi * 4e-4), 1e-3);
    }
  }
  // A folder that is a file: the error names it, and nothing is left half written.
  std::ofstream(dir / "taken") << "x";
  EXPECT_THROW(
      {
        try {
          (void)export_radiance(*bundle, (dir / "taken").string());
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("taken"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  fs::remove_all(dir);
}

}  // namespace test_radiance_export
}  // namespace walk::compiler
