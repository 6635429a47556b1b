// The map view (the paper's floor plan): a top-down view cut above the viewer's storey, in the top-right
// corner, with the viewer as a red arrow. Checked where the plan's geometry puts the floors and the viewer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace map_overlay_test {  // named, not anonymous: the suite compiles as unity batches

class MapOverlayTest : public ::testing::TestWithParam<BackendKind> {};

TEST_P(MapOverlayTest, FloorsAndTheViewerAppearWhereThePlanPutsThem) {
  auto backend = headless(GetParam());
  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "map");
  Renderer renderer(*bundle);
  const View view = looking_along_x(-1.0);  // eye at (2, 2, 1.5)
  renderer.draw(view, kWidth, kHeight);
  const Image plain = renderer.read_pixels(kWidth, kHeight);
  renderer.set_map_overlay(true, 0.9f);
  renderer.draw(view, kWidth, kHeight);
  const Image map = renderer.read_pixels(kWidth, kHeight);

  // The square: 0.9 x 120 = 108 pixels, 8 from the top and right edges; bounds 8 x 4 m around (4, 2) with
  // 5 % margin: 8.4 m across.
  const int side = 108, left = kWidth - side - 8, top = 8;
  auto to_pixel = [&](double x, double y) {
    const double half = 4.0 * 1.05;
    return std::pair{int(left + (1.0 + (x - 4.0) / half) * 0.5 * side),
                     int(top + (1.0 - (y - 2.0) / half) * 0.5 * side)};
  };
  auto expect_floor = [&](double x, double y, bool room_b) {
    const auto [px, py] = to_pixel(x, y);
    const glm::dvec3 floor = radiosity(scene, room_b, scene.floor_factor, 1, 1);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(int(map.pixel(px, py)[k]), expected_byte(floor[k], scene.exposure), 2)
          << (room_b ? "B" : "A") << "'s floor at " << px << "," << py << ", channel " << k;
  };
  expect_floor(1.0, 1.0, false);  // ceilings (3 m) are above the 2 m cut, so the floors show
  expect_floor(6.5, 3.0, true);

  // The viewer's arrow: red pixels whose centre is near the eye's place on the plan.
  double sx = 0.0, sy = 0.0;
  int red = 0;
  for (int y = top; y < top + side; ++y)
    for (int x = left; x < left + side; ++x) {
      const std::uint8_t* p = map.pixel(x, y);
      if (p[0] > 200 && p[1] < 40 && p[2] < 40) sx += x, sy += y, ++red;
    }
  ASSERT_GT(red, 3);
  const auto [ex, ey] = to_pixel(2.0, 2.0);
  EXPECT_NEAR(sx / red, ex, 3.0);
  EXPECT_NEAR(sy / red, ey, 3.0);
  // The arrow points where the viewer looks (-x): more red pixels left of the eye's centre than right.
  int left_of = 0, right_of = 0;
  for (int y = ey - 5; y <= ey + 5; ++y)
    for (int x = ex - 6; x <= ex + 6; ++x) {
      const std::uint8_t* p = map.pixel(x, y);
      if (p[0] > 200 && p[1] < 40 && p[2] < 40) (x < ex ? left_of : right_of) += 1;
    }
  EXPECT_GT(left_of, 0);

  // Outside the square the frame is the plain one.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < left; ++x)
      ASSERT_EQ(0, std::memcmp(map.pixel(x, y), plain.pixel(x, y), 4)) << x << "," << y;
}

// The compile's largest leak path (LEAK) is drawn on the map in yellow, from the seed to the opening; a
// bundle without one shows no yellow.
TEST_P(MapOverlayTest, TheLeakPathIsDrawnFromTheSeedToTheOpening) {
  auto backend = headless(GetParam());
  TwoRooms scene;
  model::BundleContents contents = make_two_rooms(scene);
  const auto& dir = test_folder();
  const int side = 108, left = kWidth - side - 8, top = 8;
  auto to_pixel = [&](double x, double y) {
    const double half = 4.0 * 1.05;
    return std::pair{int(left + (1.0 + (x - 4.0) / half) * 0.5 * side),
                     int(top + (1.0 - (y - 2.0) / half) * 0.5 * side)};
  };
  auto yellow_at = [](const Image& image, int px, int py) {
    int n = 0;
    for (int y = py - 2; y <= py + 2; ++y)
      for (int x = px - 2; x <= px + 2; ++x) {
        const std::uint8_t* p = image.pixel(x, y);
        n += p[0] > 200 && p[1] > 200 && p[2] < 40 ? 1 : 0;
      }
    return n;
  };
  for (const bool leaking : {false, true}) {
    contents.leak_path.clear();
    if (leaking) contents.leak_path = {{1.0f, 3.0f, 1.5f}, {4.0f, 3.0f, 1.0f}, {7.5f, 0.5f, 0.0f}};
    const std::string path = (dir / (leaking ? "leak.walk" : "sealed.walk")).string();
    model::write_bundle(path, contents);
    const auto bundle = model::Bundle::open(path);
    Renderer renderer(*bundle);
    renderer.set_map_overlay(true, 0.9f);
    renderer.draw(looking_along_x(-1.0), kWidth, kHeight);
    const Image map = renderer.read_pixels(kWidth, kHeight);
    int yellow = 0;
    for (int y = top; y < top + side; ++y)
      for (int x = left; x < left + side; ++x) yellow += yellow_at(map, x, y) > 0 ? 1 : 0;
    if (!leaking) {
      EXPECT_EQ(yellow, 0);
      continue;
    }
    EXPECT_GT(yellow, 20);
    // On the path: the seed, a bend and the opening, and half way along each segment; not off it.
    for (const auto& [x, y] : {std::pair{1.0, 3.0}, {2.5, 3.0}, {4.0, 3.0}, {5.75, 1.75}, {7.4, 0.6}}) {
      const auto [px, py] = to_pixel(x, y);
      EXPECT_GT(yellow_at(map, px, py), 0) << "at " << x << "," << y;
    }
    const auto [fx, fy] = to_pixel(6.5, 3.5);
    EXPECT_EQ(yellow_at(map, fx, fy), 0) << "off the path";
  }
}

INSTANTIATE_TEST_SUITE_P(Headless, MapOverlayTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace map_overlay_test
}  // namespace walk::render::test
