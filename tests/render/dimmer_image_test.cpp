// Live light mixing through whole images (issue 7's "must show"): each room on its own circuit, so a dimmer's
// effect is confined to its room's pixels and can be checked pixel by pixel against the display formula.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace dimmer_image_test {  // named, not anonymous: the suite compiles as unity batches

// Room A on circuit 0 only, room B on circuit 1 only.
TwoRooms separate_circuits() {
  TwoRooms scene;
  scene.circuit_a[0] = 60.0;
  scene.circuit_a[1] = 0.0;
  scene.circuit_b[0] = 0.0;
  scene.circuit_b[1] = 50.0;
  return scene;
}

// Linear radiosity (W/m2) shown by an 8-bit display value: the inverse of the shader's sRGB encoding.
double decode(int byte, double exposure) {
  const double e = byte / 255.0;
  return (e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4)) * exposure;
}

class DimmerImageTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override { backend_ = headless(GetParam()); }
  Image frame(Renderer& renderer, std::vector<float> levels, const View& view) {
    renderer.set_dimmers(levels);
    renderer.draw(view, kWidth, kHeight);
    return renderer.read_pixels(kWidth, kHeight);
  }
  std::unique_ptr<Backend> backend_;
};

// Looking at A's outer wall from inside A: every pixel is room A (wall, floor, ceiling, side walls).
View inside_a() {
  View view = looking_along_x(-1.0, 3.5);
  view.forward = {-1.0, 0.3, -0.1};
  return view;
}

TEST_P(DimmerImageTest, DimmerAtZeroLeavesOnlyAmbientInItsRoom) {
  const TwoRooms scene = separate_circuits();
  auto bundle = open_two_rooms(scene, "dimmer_zero");
  TwoRooms dark = scene;  // the same rooms with no circuit light at all: ambient only
  dark.circuit_a[0] = 0.0;
  dark.circuit_b[1] = 0.0;
  auto dark_bundle = open_two_rooms(dark, "dimmer_zero_dark");
  Renderer renderer(*bundle), dark_renderer(*dark_bundle);

  const Image off = frame(renderer, {0.0f, 1.0f}, inside_a());
  const Image ambient = frame(dark_renderer, {1.0f, 1.0f}, inside_a());
  const Image lit = frame(renderer, {1.0f, 1.0f}, inside_a());
  int differ_from_lit = 0;
  for (std::size_t i = 0; i < off.rgba.size(); ++i) {
    ASSERT_NEAR(int(off.rgba[i]), int(ambient.rgba[i]), 1) << "byte " << i << ": room A at dimmer 0";
    differ_from_lit += off.rgba[i] != lit.rgba[i];
  }
  EXPECT_GT(differ_from_lit, int(off.rgba.size() / 2))
      << "the lit frame must differ, or the test shows nothing";
  // And against the formula: A's wall at ambient only.
  const glm::dvec3 expected = radiosity(scene, false, scene.wall_factor, 0, 0);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(int(centre(off)[k]), expected_byte(expected[k], scene.exposure), 2) << "channel " << k;

  // Room B, seen through the opening, keeps its light when A's dimmer goes to 0.
  const Image b_with_a_on = frame(renderer, {1.0f, 1.0f}, looking_along_x(+1.0));
  const Image b_with_a_off = frame(renderer, {0.0f, 1.0f}, looking_along_x(+1.0));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(centre(b_with_a_on)[k], centre(b_with_a_off)[k]) << "channel " << k;
}

// At 0.5 the circuit's share of linear radiosity halves. Stated tolerance, per pixel and channel: what one
// 8-bit step means in linear terms at each of the two values compared (the display's own resolution), plus
// the llvmpipe's rounding of one step. Only pixels whose share is at least 20 steps are compared.
TEST_P(DimmerImageTest, DimmerAtHalfHalvesItsRoomsLinearIntensity) {
  const TwoRooms scene = separate_circuits();
  auto bundle = open_two_rooms(scene, "dimmer_half");
  Renderer renderer(*bundle);
  const Image zero = frame(renderer, {0.0f, 1.0f}, inside_a());
  const Image half = frame(renderer, {0.5f, 1.0f}, inside_a());
  const Image full = frame(renderer, {1.0f, 1.0f}, inside_a());
  const double x = scene.exposure;
  auto step = [&](int byte) { return decode(std::min(255, byte + 1), x) - decode(std::max(0, byte - 1), x); };
  int compared = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < full.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const int b0 = zero.rgba[i], bh = half.rgba[i], bf = full.rgba[i];
    if (bf >= 255) continue;  // clipped: the halving is not visible there
    const double share_full = decode(bf, x) - decode(b0, x);
    const double share_half = decode(bh, x) - decode(b0, x);
    if (share_full < 20.0 * step(bf) / 2.0) continue;
    const double tolerance = step(bh) + 0.5 * step(bf) + step(b0);
    worst = std::max(worst, std::abs(share_half - 0.5 * share_full) / tolerance);
    ASSERT_NEAR(share_half, 0.5 * share_full, tolerance) << "byte " << i;
    ++compared;
  }
  EXPECT_GT(compared, int(full.rgba.size() / 2)) << "too few pixels bright enough to compare";
  std::cout << "[ dimmer   ] " << compared << " channels at 0.5: worst error " << worst
            << " of the stated tolerance\n";
}

// The kiosk's white luminance replaces the bundle's exposure: at twice the exposure every pixel shows the
// same linear light at half the display value (to the 8-bit steps), and handing it back restores the frame.
TEST_P(DimmerImageTest, ExposureOverrideScalesTheDisplayAndHandsBack) {
  const TwoRooms scene = separate_circuits();
  auto bundle = open_two_rooms(scene, "exposure_override");
  Renderer renderer(*bundle);
  const Image normal = frame(renderer, {1.0f, 1.0f}, inside_a());
  const double x = scene.exposure;
  renderer.set_exposure(float(2.0 * x));
  const Image dimmer = frame(renderer, {1.0f, 1.0f}, inside_a());
  int compared = 0;
  for (std::size_t i = 0; i < normal.rgba.size(); ++i) {
    if (i % 4 == 3 || normal.rgba[i] >= 255 || normal.rgba[i] < 20) continue;
    const int b = normal.rgba[i], d = dimmer.rgba[i];
    const double tolerance =
        decode(d + 1, 2.0 * x) - decode(d - 1, 2.0 * x) + decode(b + 1, x) - decode(b - 1, x);
    ASSERT_NEAR(decode(d, 2.0 * x), decode(b, x), tolerance) << "byte " << i;
    ASSERT_LT(d, b) << "byte " << i;
    ++compared;
  }
  EXPECT_GT(compared, int(normal.rgba.size() / 4));
  renderer.set_exposure(std::nullopt);
  EXPECT_EQ(frame(renderer, {1.0f, 1.0f}, inside_a()).rgba, normal.rgba);
}

// Every pixel's every channel is non-decreasing as one dimmer rises in steps of 0.05, and the ends differ.
TEST_P(DimmerImageTest, BlendingIsMonotoneBetweenLevels) {
  const TwoRooms scene = separate_circuits();
  auto bundle = open_two_rooms(scene, "dimmer_monotone");
  Renderer renderer(*bundle);
  View view = looking_along_x(+1.0, 1.0);  // A's walls and, through the opening, B
  Image previous = frame(renderer, {0.0f, 0.3f}, view);
  const Image first = previous;
  for (int s = 1; s <= 20; ++s) {
    const Image next = frame(renderer, {float(s) / 20.0f, 0.3f}, view);
    for (std::size_t i = 0; i < next.rgba.size(); ++i)
      ASSERT_GE(int(next.rgba[i]), int(previous.rgba[i])) << "level " << s / 20.0 << ", byte " << i;
    previous = next;
  }
  int risen = 0;
  for (std::size_t i = 0; i < first.rgba.size(); ++i) risen += previous.rgba[i] > first.rgba[i] + 20;
  EXPECT_GT(risen, int(first.rgba.size() / 4));
}

INSTANTIATE_TEST_SUITE_P(Headless, DimmerImageTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace dimmer_image_test
}  // namespace walk::render::test
