// Head-coupled perspective through OSMesa: the shared wall of the two-room scene is the screen (x = 4,
// y 1..3, z 0.5..2, 2 x 1.5 m on 160 x 120 pixels: 80 pixels per metre). What lies on the screen plane stays
// on its pixel wherever the head is (zero parallax); what lies d behind it moves by s * d / (D + d) on the
// screen for a head shift s at distance D, as through a window.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "model/error.hpp"
#include "render/camera.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace screen_view_test {  // named, not anonymous: the suite compiles as unity batches

constexpr double kPixelsPerMetre = 80.0;
constexpr double kScreenTop = 2.0;
constexpr double kScreenLeft = 3.0;  // y of the screen's left edge, seen from room A looking along +x

ScreenRect shared_wall_screen() {
  return {{4.0, 3.0, 0.5}, {4.0, 1.0, 0.5}, {4.0, 3.0, kScreenTop}};
}

View window_view(const glm::dvec3& eye) {
  View v;
  v.eye = eye;
  v.forward = {1.0, 0.0, 0.0};
  v.screen = shared_wall_screen();
  return v;
}

class ScreenViewTest : public ::testing::Test {
 protected:
  void SetUp() override {
    backend_ = headless(BackendKind::OSMesa);
    bundle_ = open_two_rooms(scene_, "screen_view");
  }
  Image render(const View& view) {
    Renderer r(*bundle_);
    r.draw(view, kWidth, kHeight);
    return r.read_pixels(kWidth, kHeight);
  }
  std::unique_ptr<Backend> backend_;
  TwoRooms scene_;
  std::unique_ptr<model::Bundle> bundle_;
};

// Room B is blue (albedo 0.2, 0.5, 0.8), room A grey: a pixel shows B when blue clearly exceeds red.
bool shows_room_b(const std::uint8_t* p) {
  return int(p[2]) > int(p[0]) + 20;
}

// The columns where the middle row turns from A's wall to the opening and back.
std::pair<int, int> opening_columns(const Image& image) {
  const int row = kHeight / 2;
  int first = -1, last = -1;
  for (int x = 0; x < kWidth; ++x)
    if (shows_room_b(image.pixel(x, row))) {
      if (first < 0) first = x;
      last = x;
    }
  return {first, last};
}

// Sub-pixel row where a column turns from colour `upper` to colour `lower` (nearest of the two per pixel).
std::optional<double> edge_row(const Image& image, int column, const std::uint8_t* upper,
                               const std::uint8_t* lower, int from, int to) {
  auto distance = [](const std::uint8_t* a, const std::uint8_t* b) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
  };
  for (int y = from; y < to; ++y)
    if (distance(image.pixel(column, y), lower) < distance(image.pixel(column, y), upper)) return double(y);
  return std::nullopt;
}

TEST_F(ScreenViewTest, PointsOnTheScreenPlaneStayOnTheirPixelWhereverTheHeadIs) {
  // The opening's sides (y 2.5 and 1.5) lie in the screen plane: columns (3 - 2.5) * 80 = 40 and 120.
  const int left_expected = int((kScreenLeft - 2.5) * kPixelsPerMetre);
  const int right_expected = int((kScreenLeft - 1.5) * kPixelsPerMetre) - 1;
  for (const glm::dvec3 eye :
       {glm::dvec3(2.0, 2.0, 1.5), glm::dvec3(2.5, 1.6, 1.3), glm::dvec3(1.5, 2.4, 1.7),
        glm::dvec3(3.2, 2.9, 1.2), glm::dvec3(1.0, 1.2, 1.9)}) {
    const auto [first, last] = opening_columns(render(window_view(eye)));
    EXPECT_NEAR(first, left_expected, 1) << "eye " << eye.x << "," << eye.y << "," << eye.z;
    EXPECT_NEAR(last, right_expected, 1) << "eye " << eye.x << "," << eye.y << "," << eye.z;
  }
}

TEST_F(ScreenViewTest, DepthBehindTheScreenMovesWithTheHeadAsThroughAWindow) {
  // Room B's far wall meets its floor at x = 8 (d = 4 m behind the screen); the eye is D = 2 m in front.
  constexpr double kD = 2.0, kDepth = 4.0;
  const int column = int((kScreenLeft - 2.0) * kPixelsPerMetre);  // y = 2: through the middle of the opening
  auto edge_for = [&](double eye_z) {
    const Image image = render(window_view({4.0 - kD, 2.0, eye_z}));
    // Reference colours from the same image: B's far wall straight ahead, B's floor low in the opening.
    const std::uint8_t* wall = image.pixel(column, int((kScreenTop - eye_z) * kPixelsPerMetre));
    const std::uint8_t* floor = image.pixel(column, kHeight - 3);
    EXPECT_TRUE(shows_room_b(wall) && shows_room_b(floor));
    const auto row =
        edge_row(image, column, wall, floor, int((kScreenTop - eye_z) * kPixelsPerMetre), kHeight);
    EXPECT_TRUE(row.has_value());
    return row.value_or(-1000.0);
  };
  const double rest = edge_for(1.5);
  // At rest the edge is where the line from the eye to (8, 2, 0) crosses the screen: z = 1.5 * d / (D + d).
  EXPECT_NEAR(rest, (kScreenTop - 1.5 * kDepth / (kD + kDepth)) * kPixelsPerMetre, 1.0);
  for (const double s : {0.2, -0.25, 0.1}) {
    const double moved = edge_for(1.5 + s);
    const double expected_pixels = s * kDepth / (kD + kDepth) * kPixelsPerMetre;  // up the screen
    EXPECT_NEAR(rest - moved, expected_pixels, 1.0) << "head shift " << s << " m";
  }
}

TEST(ScreenViewMath, ScreensThatAreNotRectanglesOrEyesBehindThemAreErrors) {
  View v = window_view({2.0, 2.0, 1.5});
  EXPECT_NO_THROW((void)view_projection(v, 1.0));
  v.eye = {5.0, 2.0, 1.5};  // behind the screen
  EXPECT_THROW((void)view_projection(v, 1.0), Error);
  v.eye = {4.0, 2.0, 1.5};  // on its plane
  EXPECT_THROW((void)view_projection(v, 1.0), Error);
  ScreenRect skew = shared_wall_screen();
  skew.upper_left.y += 0.5;
  EXPECT_NE(screen_problem(skew).find("rectangle"), std::string::npos);
  ScreenRect point = shared_wall_screen();
  point.lower_right = point.lower_left;
  EXPECT_NE(screen_problem(point).find("coincide"), std::string::npos);
  EXPECT_EQ(screen_problem(shared_wall_screen()), "");
}

}  // namespace screen_view_test
}  // namespace walk::render::test
