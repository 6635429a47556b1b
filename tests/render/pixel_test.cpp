// Pixels of the two-room scene through each headless backend, against the display formula computed here:
// colour = albedo * ambient + sum_c level[c] * L[v][c], divided by exposure, sRGB encoded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "model/error.hpp"
#include "render/display_light.hpp"
#include "render/light_mixer.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace pixel_test {  // named, not anonymous: the suite compiles as unity batches

constexpr int kTolerance = 2;  // 8-bit steps: llvmpipe's float-to-unorm rounding and interpolation

void expect_colour(const std::uint8_t* pixel, const glm::dvec3& linear, double exposure, const char* what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(int(pixel[k]), expected_byte(linear[k], exposure), kTolerance) << what << ", channel " << k;
  EXPECT_EQ(pixel[3], 255) << what;
}

class PixelTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override { backend_ = headless(GetParam()); }
  Image render(const model::Bundle& bundle, const View& view, Renderer* existing = nullptr) {
    Renderer local(bundle);
    Renderer& r = existing ? *existing : local;
    r.set_frustum_culling(frustum_culling_);
    r.set_nearest_first(nearest_first_, run_triangles_);
    r.draw(view, kWidth, kHeight);
    stats_ = r.last_stats();
    return r.read_pixels(kWidth, kHeight);
  }
  std::unique_ptr<Backend> backend_;
  FrameStats stats_;
  bool frustum_culling_ = true;  // off where a test counts the PVS's polygons
  bool nearest_first_ = true;    // off where a test counts the ranges the compiler's order merges
  std::uint32_t run_triangles_ = kNearestFirstRunTriangles;
  TwoRooms scene_;
};

TEST_P(PixelTest, WallStraightAheadHasTheFormulaColour) {
  auto bundle = open_two_rooms(scene_, "wall_ahead");
  const Image image = render(*bundle, looking_along_x(-1.0));
  expect_colour(centre(image), radiosity(scene_, false, scene_.wall_factor, 1, 1), scene_.exposure,
                "A's outer wall");
  EXPECT_EQ(stats_.cell, 0u);
}

TEST_P(PixelTest, OpeningShowsTheSecondRoom) {
  auto bundle = open_two_rooms(scene_, "opening");
  frustum_culling_ = false;
  const Image image = render(*bundle, looking_along_x(+1.0));
  expect_colour(centre(image), radiosity(scene_, true, scene_.wall_factor, 1, 1), scene_.exposure,
                "B's far wall");
  // Beside the opening (a quarter of the way in from the left edge: y > 2.5) is A's copy of the shared wall.
  expect_colour(image.pixel(kWidth / 8, kHeight / 2), radiosity(scene_, false, scene_.wall_factor, 1, 1),
                scene_.exposure, "A's shared wall");
  // Every polygon but the opening: 6 + 2 per room (outer walls, floor, ceiling, sides, three door pieces).
  EXPECT_EQ(stats_.polygons_drawn, 16u);
  EXPECT_EQ(stats_.triangles_drawn, 32u);
  nearest_first_ = false;
  EXPECT_EQ(render(*bundle, looking_along_x(+1.0)).rgba, image.rgba) << "the compiler's order";
  EXPECT_EQ(stats_.draw_ranges, 1u) << "the opening is not laid out, so the rooms' clusters meet";
}

TEST_P(PixelTest, TopRowIsFirst) {
  auto bundle = open_two_rooms(scene_, "rows");
  // 3.9 m from the wall, the 60 degree view reaches past the ceiling at the top and the floor at the bottom.
  const Image image = render(*bundle, looking_along_x(-1.0, 3.9));
  expect_colour(image.pixel(kWidth / 2, 0), radiosity(scene_, false, scene_.ceiling_factor, 1, 1),
                scene_.exposure, "top row: ceiling");
  expect_colour(image.pixel(kWidth / 2, kHeight - 1), radiosity(scene_, false, scene_.floor_factor, 1, 1),
                scene_.exposure, "bottom row: floor");
}

TEST_P(PixelTest, DimmersMixCircuitsWithoutReupload) {
  auto bundle = open_two_rooms(scene_, "dimmers");
  Renderer renderer(*bundle);
  const View view = looking_along_x(+1.0);
  const glm::dvec3 full = radiosity(scene_, true, scene_.wall_factor, 1, 1);

  const std::vector<float> off{1.0f, 0.0f};
  renderer.set_dimmers(off);
  const Image dark = render(*bundle, view, &renderer);
  const glm::dvec3 ambient_and_c0 = radiosity(scene_, true, scene_.wall_factor, 1, 0);
  expect_colour(centre(dark), ambient_and_c0, scene_.exposure, "circuit 1 off");

  const std::vector<float> half{0.5f};  // only circuit 0 given: circuit 1 keeps 0
  renderer.set_dimmers(half);
  EXPECT_FLOAT_EQ(renderer.dimmers()[1], 0.0f);
  const std::vector<float> both{1.0f, 0.5f};
  renderer.set_dimmers(both);
  const Image halved = render(*bundle, view, &renderer);
  const glm::dvec3 expected_half = radiosity(scene_, true, scene_.wall_factor, 1, 0.5);
  expect_colour(centre(halved), expected_half, scene_.exposure, "circuit 1 at 0.5");
  // In linear terms: circuit 1's share at 0.5 is half its share at 1, to within what one 8-bit step at this
  // brightness can resolve (decode the byte, compare with 4% of the full contribution as the tolerance).
  auto decode = [&](int byte) {
    const double e = byte / 255.0;
    return (e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4)) * scene_.exposure;
  };
  for (int k = 1; k < 3; ++k) {  // green and blue: the red channel of B is too dark to resolve 4%
    const double share_full = full[k] - ambient_and_c0[k];
    const double share_half = decode(centre(halved)[k]) - decode(centre(dark)[k]);
    EXPECT_NEAR(share_half / share_full, 0.5, 0.04) << "channel " << k;
  }
}

TEST_P(PixelTest, BackFacesAreCulledUnlessTurnedOff) {
  auto bundle = open_two_rooms(scene_, "culling");
  // From outside A, behind its outer wall: that wall faces away, so culling shows the rooms through it.
  const View outside = looking_along_x(+1.0, -2.0);
  Renderer renderer(*bundle);
  const Image culled = render(*bundle, outside, &renderer);
  expect_colour(centre(culled), radiosity(scene_, true, scene_.wall_factor, 1, 1), scene_.exposure,
                "through A's culled outer wall and the opening");
  renderer.set_backface_culling(false);
  const Image drawn = render(*bundle, outside, &renderer);
  expect_colour(centre(drawn), radiosity(scene_, false, scene_.wall_factor, 1, 1), scene_.exposure,
                "A's outer wall from behind");
}

TEST_P(PixelTest, OnlyThePvsOfTheEyesCellIsDrawn) {
  scene_.cell_a_sees_b = false;
  auto bundle = open_two_rooms(scene_, "pvs");
  frustum_culling_ = false;
  const Image from_a = render(*bundle, looking_along_x(+1.0));
  EXPECT_EQ(stats_.cell, 0u);
  EXPECT_EQ(stats_.polygons_drawn, 8u);
  const std::uint8_t* p = centre(from_a);
  EXPECT_EQ(p[0] + p[1] + p[2], 0) << "room B is not in A's PVS, so the opening shows the clear colour";
  const Image from_b = render(*bundle, looking_along_x(+1.0, 6.0));
  EXPECT_EQ(stats_.cell, 1u);
  EXPECT_EQ(stats_.polygons_drawn, 16u);
  expect_colour(centre(from_b), radiosity(scene_, true, scene_.wall_factor, 1, 1), scene_.exposure, "from B");
}

TEST_P(PixelTest, GlassIsBlendedOverTheRoomBehindIt) {
  scene_.glass_door = true;
  auto bundle = open_two_rooms(scene_, "glass");
  frustum_culling_ = false;
  Renderer renderer(*bundle);
  renderer.set_glass_opacity(0.25f);
  nearest_first_ = false;  // the opaque clusters in one range, the glass door laid out after them
  EXPECT_EQ(render(*bundle, looking_along_x(+1.0), &renderer).rgba.size(), std::size_t(kWidth * kHeight * 4));
  EXPECT_EQ(stats_.draw_ranges, 2u);
  nearest_first_ = true;
  run_triangles_ = 0;  // each cluster on its own: the rooms' few small clusters would go as one run
  const Image image = render(*bundle, looking_along_x(+1.0), &renderer);
  EXPECT_EQ(stats_.polygons_drawn, 17u);
  EXPECT_GT(stats_.draw_ranges, 2u) << "nearest first splits the compiler's opaque range";
  const glm::dvec3 glass = radiosity(scene_, false, scene_.wall_factor, 1, 1);
  const glm::dvec3 behind = radiosity(scene_, true, scene_.wall_factor, 1, 1);
  for (int k = 0; k < 3; ++k) {
    // Blended in display values: 0.25 * glass + 0.75 * what is behind.
    const double expected =
        0.25 * expected_byte(glass[k], scene_.exposure) + 0.75 * expected_byte(behind[k], scene_.exposure);
    EXPECT_NEAR(centre(image)[k], expected, kTolerance + 0.5) << "channel " << k;
  }
  EXPECT_EQ(centre(image)[3], 255);
}

// At the limit the bundle is drawn, its second circuit's light moved onto the last circuit, whose level is
// the levels buffer's last texel.
TEST_P(PixelTest, CircuitsUpToTheLimitAreDrawnAndOneMoreIsAClearError) {
  scene_.circuits = kMaxCircuits;
  {
    model::BundleContents contents = make_two_rooms(scene_);
    const auto last = std::uint32_t(kMaxCircuits - 1);
    for (model::LightEntry& e : contents.light.entries)
      if (e.circuit == 1) e.circuit = last;
    auto bundle = open_bundle(contents, "circuits_at_limit");
    Renderer renderer(*bundle);
    std::vector<float> levels(std::size_t(kMaxCircuits), 1.0f);
    levels[last] = 0.5f;
    renderer.set_dimmers(levels);
    expect_colour(centre(render(*bundle, looking_along_x(+1.0), &renderer)),
                  radiosity(scene_, true, scene_.wall_factor, 1, 0.5), scene_.exposure, "at the limit");
  }
  scene_.circuits = kMaxCircuits + 1;
  auto bundle = open_two_rooms(scene_, "circuits");
  try {
    Renderer renderer(*bundle);
    FAIL() << kMaxCircuits + 1 << " circuits accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxCircuits + 1) + " circuits"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("at most " + std::to_string(kMaxCircuits)), std::string::npos)
        << e.what();
  }
}

// A building with many circuits, each reaching a few rooms: the two rooms' light moved onto circuits 37 and
// 1,000 of 1,024 (past the 512 a uniform array of dimmer levels held, as the generated L building's 850
// are), the rest dark. Each vertex keeps two entries, and the dimmers of those circuits mix them as the
// two-circuit scene's do.
TEST_P(PixelTest, ManyCircuitsMixOnlyTheCircuitsThatReachAVertex) {
  scene_.circuits = 1024;
  model::BundleContents contents = make_two_rooms(scene_);
  const std::size_t n = 1024, far_a = 37, far_b = 1000;
  std::vector<float> dense = contents.light.dense(n);
  for (std::size_t v = 0; v < contents.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      std::swap(dense[(v * n + 0) * 3 + k], dense[(v * n + far_a) * 3 + k]);
      std::swap(dense[(v * n + 1) * 3 + k], dense[(v * n + far_b) * 3 + k]);
    }
  const std::size_t dark = contents.vertices.size() - 1;  // a vertex no circuit reaches
  std::fill_n(dense.begin() + std::ptrdiff_t(dark * n * 3), n * 3, 0.0f);
  contents.light = model::LightRows::from_dense(dense, n);
  auto bundle = open_bundle(contents, "many_circuits");
  const DisplayLight light(*bundle, DisplayLightForm::AsCompiled);
  EXPECT_EQ(light.full_entries().size(), 2 * dark) << "two of 1,024 circuits a vertex";
  EXPECT_EQ(light.ranges()[dark].full_first, VertexLightRange::kNone);
  EXPECT_EQ(light.ranges()[dark - 1].full_first, 2 * (dark - 1));
  const std::vector<float> all_on(n, 1.0f);
  EXPECT_EQ(light.mixed(dark, all_on), glm::vec3(0.0f));
  EXPECT_EQ(light.mixed(dark - 1, all_on)[2],
            dense[((dark - 1) * n + far_a) * 3 + 2] + dense[((dark - 1) * n + far_b) * 3 + 2]);
  Renderer renderer(*bundle);
  std::vector<float> levels(n, 1.0f);
  levels[far_b] = 0.5f;
  renderer.set_dimmers(levels);
  const Image image = render(*bundle, looking_along_x(+1.0), &renderer);
  expect_colour(centre(image), radiosity(scene_, true, scene_.wall_factor, 1, 0.5), scene_.exposure,
                "circuit 1000 at 0.5");
  levels[far_a] = 0.0f;
  renderer.set_dimmers(levels);
  const Image dimmed = render(*bundle, looking_along_x(+1.0), &renderer);
  expect_colour(centre(dimmed), radiosity(scene_, true, scene_.wall_factor, 0, 0.5), scene_.exposure,
                "circuit 37 off too");
  // The coarse level's flat polygon light (mixed in the shader from each polygon's own circuits) agrees.
  renderer.draw(looking_along_x(+1.0), kWidth, kHeight, DrawOptions{.patch_weight = 0.0f});
  expect_colour(centre(renderer.read_pixels(kWidth, kHeight)),
                radiosity(scene_, true, scene_.wall_factor, 0, 0.5), scene_.exposure, "coarse level");
}

TEST_P(PixelTest, ReadingAtAnotherSizeIsAnError) {
  auto bundle = open_two_rooms(scene_, "size");
  Renderer renderer(*bundle);
  renderer.draw(looking_along_x(1.0), kWidth, kHeight);
  EXPECT_THROW((void)renderer.read_pixels(kWidth * 2, kHeight), Error);
}

INSTANTIATE_TEST_SUITE_P(Headless, PixelTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace pixel_test
}  // namespace walk::render::test
