// Not a pass/fail check: prints milliseconds per 1280x720 frame of the two-room scene on each headless
// backend, and writes the views as PNGs under the build folder for a person to look at.
#include <glad/gl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>

#include "compiler/pipeline.hpp"
#include "model/bundle.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace frame_time_test {  // named, not anonymous: the suite compiles as unity batches

constexpr int kFrameWidth = 1280;
constexpr int kFrameHeight = 720;

double ms_per_frame(Renderer& renderer, const View& view, int frames) {
  renderer.draw(view, kFrameWidth, kFrameHeight);  // first frame builds the cell's draw list
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) renderer.draw(view, kFrameWidth, kFrameHeight);
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
}

TEST(FrameTime, TwoRoomsAt1280x720) {
  const std::filesystem::path out = std::filesystem::path(WALK_BINARY_DIR) / "render_views";
  std::filesystem::create_directories(out);
  for (BackendKind kind : {BackendKind::OSMesa, BackendKind::EGL}) {
    auto backend = headless(kind, kFrameWidth, kFrameHeight);
    for (int subdivisions : {1, 40}) {
      TwoRooms scene;
      scene.subdivisions = subdivisions;
      auto bundle = open_two_rooms(scene, "timing" + std::to_string(subdivisions));
      Renderer renderer(*bundle);
      View view = looking_along_x(+1.0, 0.3);
      view.forward = {1.0, -0.35, -0.12};  // off-axis, so floor, ceiling, side wall and the opening all show
      const double ms = ms_per_frame(renderer, view, 20);
      std::cout << "[ frame    ] " << backend->name() << " 1280x720, "
                << renderer.last_stats().triangles_drawn << " triangles: " << ms << " ms per frame\n";
      if (subdivisions == 1) {
        const auto path = out / (std::string("two_rooms_") + backend->name() + ".png");
        write_png(path.string(), renderer.read_pixels(kFrameWidth, kFrameHeight));
        std::cout << "[ frame    ] wrote " << path.string() << "\n";
      }
    }
  }
}

TEST(FrameTime, HouseAt1280x720) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("walk_frame_time_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "house.walk").string();
  compiler::compile_to_file(std::string(WALK_SOURCE_DIR) + "/config/scenes/house.toml", path, true);
  auto bundle = model::Bundle::open(path);
  ASSERT_FALSE(bundle->luminaires().empty());
  // Under a middle-floor luminaire, looking across its room and through a door (see `walk inspect`).
  const float* lamp = bundle->luminaires()[bundle->luminaires().size() / 2].position;
  View view;
  view.eye = {lamp[0], lamp[1], lamp[2] - 1.2};
  view.forward = {-1.0, 0.1, -0.2};
  for (BackendKind kind : {BackendKind::OSMesa, BackendKind::EGL}) {
    auto backend = headless(kind, kFrameWidth, kFrameHeight);
    Renderer renderer(*bundle);
    const double ms = ms_per_frame(renderer, view, 20);
    std::cout << "[ frame    ] house, " << backend->name() << " 1280x720, "
              << renderer.last_stats().triangles_drawn << " triangles, " << bundle->circuits().size()
              << " circuits: " << ms << " ms per frame\n";
  }
  std::filesystem::remove_all(dir);
}

}  // namespace frame_time_test
}  // namespace walk::render::test
