// The Reduced level's CPU upscale (pixman): close to GL_LINEAR's sampling written out, at exact doubles, odd
// sizes and one-pixel frames, and to llvmpipe's own blit in a real frame.
#include "render/upscale.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "model/error.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace upscale_test {  // named, not anonymous: the suite compiles as unity batches

// GL_LINEAR written out in double: output pixel x samples source position (x + 0.5) * width / out_width - 0.5
// in texel-centre units, between the two nearest texels clamped to the edge, weighted by the distance.
std::vector<double> reference(const std::vector<std::uint8_t>& source, int width, int height, int out_width,
                              int out_height) {
  std::vector<double> out(std::size_t(4 * out_width * out_height));
  const auto texel = [&](int x, int y, int c) {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return double(source[std::size_t(4 * (y * width + x) + c)]);
  };
  for (int y = 0; y < out_height; ++y)
    for (int x = 0; x < out_width; ++x) {
      const double u = (x + 0.5) * width / out_width - 0.5, v = (y + 0.5) * height / out_height - 0.5;
      const int i = int(std::floor(u)), j = int(std::floor(v));
      const double fu = u - i, fv = v - j;
      for (int c = 0; c < 4; ++c)
        out[std::size_t(4 * (y * out_width + x) + c)] =
            (1 - fu) * (1 - fv) * texel(i, j, c) + fu * (1 - fv) * texel(i + 1, j, c) +
            (1 - fu) * fv * texel(i, j + 1, c) + fu * fv * texel(i + 1, j + 1, c);
    }
  return out;
}

// pixman samples at positions quantised to 1/128 of a texel on each axis and rounds its 7-bit weighted sum.
// At an exact double the positions (1/4 and 3/4) are exact, so only the rounding is left: under 1 step. At
// other ratios a position may be 1/128 off on both axes, which across a full-range edge (0 next to 255, as
// random pixels have) is up to 2 x 255 / 128 steps, plus the rounding: under 4.
constexpr double kDoubledSteps = 1.0;
constexpr double kScaledSteps = 4.0;

TEST(Upscale, CloseToGlLinearSamplingAtEverySize) {
  std::mt19937 random(7);
  // One pixel; one row and one column; exact doubles; odd sizes (the kiosk at an odd window size); more
  // rows than one band of threads.
  for (const auto& [width, height, out_width, out_height] : {std::tuple{1, 1, 2, 2},
                                                             {1, 5, 2, 10},
                                                             {5, 1, 10, 2},
                                                             {3, 3, 6, 6},
                                                             {17, 9, 34, 18},
                                                             {80, 60, 161, 121},
                                                             {64, 200, 128, 400}}) {
    std::vector<std::uint8_t> source(std::size_t(4 * width * height));
    for (auto& byte : source) byte = std::uint8_t(random() & 0xff);
    source[0] = 255;  // the extremes next to each other
    if (source.size() > 4) source[4] = 0;
    std::vector<std::uint8_t> out(std::size_t(4 * out_width * out_height), 77);
    scale_bilinear(source, width, height, out, out_width, out_height);
    const std::vector<double> exact = reference(source, width, height, out_width, out_height);
    double worst = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i) worst = std::max(worst, std::abs(double(out[i]) - exact[i]));
    const bool doubled = out_width == 2 * width && out_height == 2 * height;
    EXPECT_LT(worst, doubled ? kDoubledSteps : kScaledSteps)
        << width << "x" << height << " to " << out_width << "x" << out_height;
  }
}

TEST(Upscale, SizesThatDoNotFitAreErrors) {
  std::vector<std::uint8_t> source(4 * 6), out(16 * 6);
  EXPECT_NO_THROW(scale_bilinear(source, 3, 2, out, 6, 4));
  EXPECT_THROW(scale_bilinear(source, 2, 2, out, 6, 4), Error);
  EXPECT_THROW(scale_bilinear(source, 3, 2, out, 6, 3), Error);
  EXPECT_THROW(scale_bilinear(source, 3, 2, std::span(out).first(out.size() - 1), 6, 4), Error);
  EXPECT_THROW(scale_bilinear(source, 0, 2, out, 6, 4), Error);
  EXPECT_THROW(scale_bilinear(source, -3, -2, out, 6, 4), Error);
}

class UpscaleImageTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override { backend_ = headless(GetParam(), kWidth + 1, kHeight + 1); }
  std::unique_ptr<Backend> backend_;
};

// A half-size frame with edges and a gradient, scaled up both ways: within 1 in every channel at an exact
// double (160x120 from 80x60), within 2 at an odd size (161x121 from 80x60: pixman's 1/128-texel sampling
// steps against llvmpipe's 1/256), and different somewhere (else the switch would not have switched).
TEST_P(UpscaleImageTest, CpuUpscaleIsWithinOneOfTheBlit) {
  TwoRooms scene;
  scene.light_gradient = true;
  scene.subdivisions = 4;
  auto bundle = open_two_rooms(scene, "upscale");
  View view = looking_along_x(+1.0, 1.0);
  view.up = {0.0, std::sin(0.21), std::cos(0.21)};
  const DrawOptions reduced{.patch_weight = 1.0f, .resolution = 0.5f};
  for (const auto& [width, height] : {std::pair{kWidth, kHeight}, {kWidth + 1, kHeight + 1}}) {
    const auto frame = [&](bool cpu) {
      Renderer renderer(*bundle);
      renderer.set_cpu_upscale(cpu);
      renderer.draw(view, width, height, reduced);
      EXPECT_EQ(renderer.last_stats().resolution, 0.5f);
      return renderer.read_pixels(width, height).rgba;
    };
    const auto on_cpu = frame(true), blitted = frame(false);
    ASSERT_EQ(on_cpu.size(), blitted.size());
    int worst = 0, differing = 0;
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i < on_cpu.size(); ++i) {
      const int d = std::abs(int(on_cpu[i]) - int(blitted[i]));
      worst = std::max(worst, d);
      differing += d > 0;
      if (i % 4 == 0) colours.insert(on_cpu[i] | on_cpu[i + 1] << 8 | on_cpu[i + 2] << 16);
    }
    EXPECT_LE(worst, width == 2 * (width / 2) ? 1 : 2)
        << width << "x" << height << ": the CPU upscale against the GL_LINEAR blit";
    EXPECT_GT(colours.size(), 50u) << "the frame has edges and a gradient to filter";
    EXPECT_GT(differing, 0) << "the CPU path was taken";
  }
}

INSTANTIATE_TEST_SUITE_P(Headless, UpscaleImageTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace upscale_test
}  // namespace walk::render::test
