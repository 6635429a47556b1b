// The `walk render` command end to end: compile the sample house with `walk compile`, render a view of its
// ground floor with each headless backend, and check the PNG holds a lit room.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "model/bundle.hpp"
#include "two_rooms.hpp"

namespace walk::render {
namespace walk_tool_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

const std::string kWalk = std::string(WALK_BINARY_DIR) + "/tools/walk";

int run(const std::string& command, std::string& output) {
  const fs::path log = fs::temp_directory_path() / ("walk_tool_test_" + std::to_string(::getpid()) + ".log");
  const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  output = text.str();
  fs::remove(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(WalkTool, HelpShowsDefaultsAndThreadsDefaultToTheCores) {
  std::string output;
  ASSERT_EQ(run(kWalk + " compile --help", output), 0) << output;
  const unsigned cores = std::clamp(std::thread::hardware_concurrency(), 1u, 256u);
  EXPECT_NE(output.find("in [1 - 256]=" + std::to_string(cores)), std::string::npos) << output;
  EXPECT_NE(output.find("TEXT=scene.walk"), std::string::npos) << output;
  ASSERT_EQ(run(kWalk + " render --help", output), 0) << output;
  EXPECT_NE(output.find("glfw or gbm"), std::string::npos) << output;
}

TEST(WalkTool, RendersACompiledHouse) {
  ASSERT_TRUE(fs::exists(kWalk)) << kWalk << " is missing: build the `walk` target as well as the tests";
  const fs::path dir = fs::temp_directory_path() / ("walk_tool_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string bundle = (dir / "house.walk").string();
  std::string output;
  ASSERT_EQ(run(kWalk + " compile " + WALK_SOURCE_DIR + "/config/scenes/house.toml -o " + bundle, output), 0)
      << output;
  // Stand 1.2 m below the first ceiling luminaire, looking across and down into its lit room: the compiler
  // may move the local origin, so the view comes from the bundle, not from fixed coordinates.
  auto opened = model::Bundle::open(bundle);
  ASSERT_FALSE(opened->luminaires().empty());
  const float* lamp = opened->luminaires()[0].position;
  auto triple = [](double x, double y, double z) {
    std::ostringstream text;
    text << x << ',' << y << ',' << z;
    return text.str();
  };
  const std::string eye = triple(lamp[0], lamp[1], lamp[2] - 1.2);
  const std::string look = triple(lamp[0] + 2.0, lamp[1] + 0.7, lamp[2] - 2.2);
  for (const char* backend : {"egl", "osmesa"}) {
    const std::string png = (dir / (std::string(backend) + ".png")).string();
    ASSERT_EQ(run(kWalk + " render " + bundle + " --eye " + eye + " --look " + look +
                      " --size 320x180 --backend " + backend + " -o " + png,
                  output),
              0)
        << output;
    EXPECT_NE(output.find(std::string("backend ") + backend), std::string::npos) << output;
    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&image, png.c_str())) << png;
    image.format = PNG_FORMAT_RGBA;
    std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(image));
    ASSERT_TRUE(png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr)) << png;
    EXPECT_EQ(image.width, 320u);
    EXPECT_EQ(image.height, 180u);
    // Most of the frame is lit wall, floor and ceiling: few pixels are the black clear colour.
    std::size_t black = 0;
    for (std::size_t i = 0; i < rgba.size(); i += 4) black += rgba[i] + rgba[i + 1] + rgba[i + 2] == 0;
    EXPECT_LT(black, rgba.size() / 4 / 4) << backend << ": " << black << " black pixels";
  }
  // A bad backend name is refused with the accepted values.
  EXPECT_NE(
      run(kWalk + " render " + bundle + " --eye " + eye + " --look " + look + " --backend vulkan", output),
      0);
  EXPECT_NE(output.find("auto, osmesa, egl, glfw"), std::string::npos) << output;
  fs::remove_all(dir);
}

}  // namespace walk_tool_test
}  // namespace walk::render

namespace walk::render {
namespace walk_tool_test {  // named, not anonymous: the suite compiles as unity batches

// `walk bench render` end to end on the four-cell test bundle, small and short: every section prints its
// rows (a smoke test: the figures themselves come from the full run in docs/RENDER.md).
TEST(WalkTool, BenchRenderWalksOnlyWhereAViewerCanStand) {
  test::TwoRooms scene;
  scene.four_cells = true;
  auto contents = test::make_two_rooms(scene);
  // Room B's two cells only the outside reaches: the scripted walk (x = 2 -> 6 m, no luminaires) leaves
  // out its half of the path there and spreads its frames over room A.
  contents.cells[2].flags = model::kCellOutside;
  contents.cells[3].flags = model::kCellOutside;
  const auto bundle = test::open_bundle(contents, "bench_render_off_walk");
  std::string output;
  ASSERT_EQ(
      run(kWalk + " bench render " + bundle->path() + " --backend osmesa --size 160x120 --frames 12", output),
      0)
      << output;
  const auto at = output.find("scripted walk: ");
  ASSERT_NE(at, std::string::npos) << output;
  const int left_out = std::stoi(output.substr(at + 15));
  EXPECT_GE(left_out, 40) << "about half of 96 path points lie in room B";
  EXPECT_LE(left_out, 56);
  EXPECT_NE(output.find("of 96 points along its path are off the walk"), std::string::npos) << output;
  EXPECT_NE(output.find("governed,moving,12,"), std::string::npos) << "still 12 frames, all in room A";
}

TEST(WalkTool, BenchRenderPrintsEverySection) {
  test::TwoRooms scene;
  scene.four_cells = true;
  scene.subdivisions = 2;
  scene.coarse_form = true;  // so the coarse form's vertices are timed shared and own
  const auto bundle = test::open_two_rooms(scene, "bench_render");
  std::string output;
  ASSERT_EQ(
      run(kWalk + " bench render " + bundle->path() + " --backend osmesa --size 160x120 --frames 12", output),
      0)
      << output;
  for (const char* row : {"bench_render,walk,unculled,12,",
                          "walk,culled,12,",
                          "walk,culled+frustum+portals,12,",
                          "walk,speedup-culled,",
                          "governed,moving,12,",
                          "level,reduced-half-res,",
                          "level,simplified,",
                          "level,coarse,",
                          "level,patches,",
                          "level,empty-frame,",
                          "level,coarsest-lod,",
                          "level,diagonals+subdivision,",
                          "order,nearest-first-simplified,6,",
                          "order,compiler-order-patches,6,",
                          "order,speedup-nearest-first-patches,",
                          "occlusion,occlusion-culled-simplified,6,",
                          "occlusion,unculled-patches,6,",
                          "occlusion,speedup-occlusion-patches,",
                          "walk,culled+frustum+portals+occlusion,12,",
                          "upscale,cpu-upscale-half-res,6,",
                          "elision,elided-simplified,6,",
                          "elision,drawn-half-res,6,",
                          "elision,speedup-elided-half-res,",
                          "upscale,blit-half-res,6,",
                          "upscale,speedup-cpu-upscale-half-res,",
                          "vertices,shared-reduced-half-res,6,",
                          "vertices,own-coarse,6,",
                          "vertices,speedup-shared-simplified,",
                          "aa,1-samples,",
                          "aa,64-samples,"})
    EXPECT_NE(output.find(row), std::string::npos) << "missing '" << row << "' in:\n" << output;
  // The culled walk draws fewer polygons than the unculled one (each room leaves out 3 of the other's).
  auto polygons = [&](const std::string& key) {
    const auto at = output.find(key);
    if (at == std::string::npos) return -1.0;
    std::stringstream line(output.substr(at, output.find('\n', at) - at));
    std::string field;
    for (int i = 0; i < 5; ++i) std::getline(line, field, ',');  // section, variant, frames, p50, p99
    std::getline(line, field, ',');
    return std::stod(field);
  };
  EXPECT_LT(polygons("walk,culled,"), polygons("walk,unculled,"));
  // The level rows count what was shaded (llvmpipe has pipeline statistics): a frame of the two rooms
  // covers most of its 160x120 pixels at least once.
  const auto patches_row = output.find("level,patches,");
  ASSERT_NE(patches_row, std::string::npos);
  const std::string row = output.substr(patches_row, output.find('\n', patches_row) - patches_row);
  const auto shaded = row.find("; ", row.find("full detail"));
  ASSERT_NE(shaded, std::string::npos) << row;
  EXPECT_GT(std::stod(row.substr(shaded + 2)), 0.5 * 160 * 120) << row;
  EXPECT_NE(row.find("vertices shaded a frame"), std::string::npos) << row;
  // Two bundles and --plot (and --no-portals and --blit-upscale, which the CLI must take): one table each
  // (one header) and a size summary with a row per bundle.
  const std::string plot = bundle->path() + ".size.png";
  std::string twice;
  ASSERT_EQ(run(kWalk + " bench render " + bundle->path() + " " + bundle->path() +
                    " --backend osmesa --size 160x120 --frames 12 --no-portals --blit-upscale --plot " + plot,
                twice),
            0)
      << twice;
  EXPECT_EQ(twice.find("scene,section"), twice.rfind("scene,section")) << "one header";
  std::ifstream summary(plot + ".csv");
  std::string line;
  int rows = 0;
  while (std::getline(summary, line)) rows += line.rfind("bench_render,", 0) == 0;
  EXPECT_EQ(rows, 2);
  // Full detail against itself: no error; the half-resolution level differs somewhere.
  const auto patches = output.find("level,patches,");
  ASSERT_NE(patches, std::string::npos);
  EXPECT_NE(output.substr(patches, output.find('\n', patches) - patches).find(",0.00000,0.00,"),
            std::string::npos);
  const auto reduced = output.find("level,reduced-half-res,");
  EXPECT_EQ(output.substr(reduced, output.find('\n', reduced) - reduced).find(",0.00000,0.00,"),
            std::string::npos);
}

}  // namespace walk_tool_test
}  // namespace walk::render
