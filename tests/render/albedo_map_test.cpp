// Albedo maps end to end: a room whose walls and floor carry a checkerboard map, compiled by the display
// compiler and drawn through OSMesa, against the same room with the map's mean as a plain colour. The
// solver must see the same reflectance (the same light), and each pixel must show that light times
// texel / mean, through every path that draws: full detail, PVS on or off, and the refined still frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../compiler/texture_files.hpp"
#include "compiler/pipeline.hpp"
#include "model/srgb.hpp"
#include "render_test_support.hpp"

namespace walk::render::test {
namespace albedo_map_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

constexpr std::uint8_t kDark = 64, kBright = 192;  // sRGB bytes of the checkerboard's two greys
// A pixel within this share of the expected ratio to the plain room is that texel: 8-bit rounding of the
// dark pixels (about 40/255) is 1.3%, the solve is the same.
constexpr double kRatioTolerance = 0.1;

double linear(std::uint8_t byte) {
  return model::srgb_decode_table()[byte];
}

// A 4 x 4 x 3 m room, faces inward, z up, a 1 m square lamp under the ceiling. Walls and floor in material
// `surface`, with coordinates of one repeat per 2 m (the checkerboard's cells are 1 m).
void write_room(const fs::path& obj, const std::string& mtl_text) {
  std::ofstream(obj.parent_path() / "room.mtl") << mtl_text << "newmtl ceiling\nKd 0.5 0.5 0.5\n"
                                                << "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n";
  std::ofstream out(obj);
  out << "mtllib room.mtl\n";
  out << "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 3\nv 4 0 3\nv 4 4 3\nv 0 4 3\n";
  out << "v 1.5 1.5 2.95\nv 1.5 2.5 2.95\nv 2.5 2.5 2.95\nv 2.5 1.5 2.95\n";
  out << "vt 0 0\nvt 2 0\nvt 2 1.5\nvt 0 1.5\nvt 2 2\nvt 0 2\n";
  out << "usemtl surface\n";
  out << "f 1/1 2/2 3/5 4/6\n";          // floor, +z
  out << "f 1/1 4/2 8/3 5/4\n";          // x = 0, +x
  out << "f 2/1 6/4 7/3 3/2\n";          // x = 4, -x
  out << "f 1/1 5/4 6/3 2/2\n";          // y = 0, +y
  out << "f 4/1 3/2 7/3 8/4\n";          // y = 4, -y
  out << "usemtl ceiling\nf 5 8 7 6\n";  // -z
  out << "usemtl lamp\nf 9 10 11 12\n";  // -z
}

class AlbedoMapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_albedo_" + std::to_string(::getpid()));
    for (const char* d : {"plain", "mapped"}) fs::create_directories(dir_ / d);
    mean_ = 0.5 * (linear(kDark) + linear(kBright));
    char kd[64];
    // The float the importer rounds the mapped material's reflectance to, so both solves are identical.
    std::snprintf(kd, sizeof kd, "%.9g", double(float(mean_)));
    write_room(dir_ / "plain" / "room.obj",
               "newmtl surface\nKd " + std::string(kd) + " " + kd + " " + kd + "\n");
    compiler::test::write_test_png((dir_ / "mapped" / "checker.png").string(), 64, 64,
                                   compiler::test::checkerboard(64, 2, kDark, kBright));
    write_room(dir_ / "mapped" / "room.obj", "newmtl surface\nKd 1 1 1\nmap_Kd checker.png\n");
    plain_ = compile("plain");
    mapped_ = compile("mapped");
    // One exposure for both, twice the automatic one, so that the map's bright texels (1.5 x the mean)
    // do not clip.
    plain_.meta.exposure = mapped_.meta.exposure = 2.0f * plain_.meta.exposure;
  }
  void TearDown() override { fs::remove_all(dir_); }

  model::BundleContents compile(const std::string& name) {
    const fs::path scene = dir_ / name / "scene.toml";
    std::ofstream(scene) << "[model]\nfile = \"room.obj\"\nunits = \"m\"\nup = \"z\"\n"
                         << "[lighting]\ngrid = 0.25\nrays_per_watt = 300\n";
    return compiler::compile_scene(compiler::load_scene_config(scene.string())).bundle;
  }
  std::unique_ptr<model::Bundle> open(const model::BundleContents& contents, const std::string& name) {
    const std::string path = (dir_ / (name + ".walk")).string();
    model::write_bundle(path, contents);
    return model::Bundle::open(path);
  }

  fs::path dir_;
  double mean_ = 0.0;
  model::BundleContents plain_, mapped_;
};

// Looking at the x = 0 wall from the room's middle (u = y / 2, v = z / 2 on it), in the bundle's local frame.
View at_the_wall(const model::BundleContents& b) {
  View view;
  view.eye = glm::dvec3(2.8, 2.0, 1.5) - glm::dvec3(b.meta.origin[0], b.meta.origin[1], b.meta.origin[2]);
  view.forward = {-1.0, 0.0, 0.0};
  return view;
}

struct Classified {
  int dark = 0, bright = 0, other = 0;
};

// Each pixel of the middle half of the frame, as its ratio to the plain room's.
Classified classify(const Image& mapped, const Image& plain, double mean) {
  const double dark = linear(kDark) / mean, bright = linear(kBright) / mean;
  Classified c;
  for (int y = kHeight / 4; y < 3 * kHeight / 4; ++y)
    for (int x = kWidth / 4; x < 3 * kWidth / 4; ++x) {
      const double ratio = linear(mapped.pixel(x, y)[1]) / std::max(linear(plain.pixel(x, y)[1]), 1e-6);
      if (std::abs(ratio / dark - 1.0) < kRatioTolerance)
        ++c.dark;
      else if (std::abs(ratio / bright - 1.0) < kRatioTolerance)
        ++c.bright;
      else
        ++c.other;
    }
  return c;
}

TEST_F(AlbedoMapTest, TheSolverSeesTheMapsMeanAndTheBundleCarriesTheMap) {
  EXPECT_TRUE(plain_.textures.empty() && plain_.polygon_textures.empty() && plain_.texels.empty())
      << "a scene without maps pays nothing";
  ASSERT_EQ(mapped_.textures.size(), 1u);
  EXPECT_EQ(mapped_.textures[0].width, 64u);
  EXPECT_NEAR(mapped_.textures[0].mean[1], mean_, 1e-6);
  ASSERT_EQ(mapped_.polygon_textures.size(), mapped_.polygons.size());
  std::size_t mapped_polygons = 0;
  for (const auto& p : mapped_.polygon_textures) mapped_polygons += p.texture == 0 ? 1 : 0;
  EXPECT_EQ(mapped_polygons, 5u) << "floor and four walls; the ceiling and the lamp have no map";
  ASSERT_EQ(plain_.vertices.size(), mapped_.vertices.size());
  for (std::size_t v = 0; v < plain_.vertices.size(); ++v)
    ASSERT_NEAR(plain_.vertices[v].albedo[1], mapped_.vertices[v].albedo[1], 1e-6) << v;
  const std::vector<float> plain_light = plain_.light.dense(plain_.circuits.size()),
                           mapped_light = mapped_.light.dense(mapped_.circuits.size());
  ASSERT_EQ(plain_light.size(), mapped_light.size());
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < plain_light.size(); ++i) {
    worst = std::max(worst, double(std::abs(plain_light[i] - mapped_light[i])));
    largest = std::max(largest, double(plain_light[i]));
  }
  EXPECT_LT(worst, 1e-6 * largest) << "the same reflectance, the same light (float rounding aside)";
  // The file round trip keeps the sections, validated.
  const auto bundle = open(mapped_, "mapped");
  EXPECT_EQ(bundle->textures().size(), 1u);
  EXPECT_EQ(bundle->texels().size(), 64u * 64u * 4u);
  EXPECT_EQ(bundle->polygon_textures().size(), bundle->polygons().size());
}

TEST_F(AlbedoMapTest, PixelsShowTheLightTimesTexelOverMeanOnEveryDrawingPath) {
  auto backend = headless(BackendKind::OSMesa);
  const auto plain = open(plain_, "plain");
  const auto mapped = open(mapped_, "mapped");
  Renderer plain_renderer(*plain), mapped_renderer(*mapped);
  const View view = at_the_wall(plain_);
  plain_renderer.draw(view, kWidth, kHeight);
  const Image plain_image = plain_renderer.read_pixels(kWidth, kHeight);
  mapped_renderer.draw(view, kWidth, kHeight);
  const Image mapped_image = mapped_renderer.read_pixels(kWidth, kHeight);
  const Classified full = classify(mapped_image, plain_image, mean_);
  const int sampled = full.dark + full.bright + full.other;
  EXPECT_GT(full.dark, sampled / 4) << "dark cells";
  EXPECT_GT(full.bright, sampled / 4) << "bright cells";
  EXPECT_LT(full.other, sampled / 8) << "only the cells' edges are in between";
  const Classified same = classify(plain_image, plain_image, mean_);
  EXPECT_EQ(same.dark + same.bright, 0) << "the classifier finds no map where there is none";

  // With the PVS off, the same pixels.
  mapped_renderer.set_pvs_culling(false);
  mapped_renderer.draw(view, kWidth, kHeight);
  const Image unculled = mapped_renderer.read_pixels(kWidth, kHeight);
  EXPECT_EQ(unculled.rgba, mapped_image.rgba);
  mapped_renderer.set_pvs_culling(true);

  // Refined to the still frame (diagonals, subdivided quads, anti-aliasing): the map stays, at the same
  // level.
  for (int i = 0; i < 64 && mapped_renderer.refine(view, kWidth, kHeight); ++i) {
  }
  for (int i = 0; i < 64 && plain_renderer.refine(view, kWidth, kHeight); ++i) {
  }
  const Classified still = classify(mapped_renderer.read_pixels(kWidth, kHeight),
                                    plain_renderer.read_pixels(kWidth, kHeight), mean_);
  EXPECT_GT(still.dark, sampled / 4);
  EXPECT_GT(still.bright, sampled / 4);
  EXPECT_LT(still.other, sampled / 6) << "anti-aliasing softens the cells' edges a little";
}

}  // namespace albedo_map_test
}  // namespace walk::render::test
