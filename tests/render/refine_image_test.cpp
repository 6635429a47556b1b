// Adaptive refinement through OSMesa and EGL: coarse-to-patch blending is monotone, accumulation lowers an
// edge aliasing measure as samples grow, and a converged renderer draws nothing.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/accumulator.hpp"
#include "render/framebuffer.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace refine_image_test {  // named, not anonymous: the suite compiles as unity batches

class RefineImageTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override { backend_ = headless(GetParam()); }
  std::unique_ptr<Backend> backend_;
};

// Rolled 12 degrees so the opening's and the room's edges are slanted: staircases to anti-alias.
View rolled_view() {
  View view = looking_along_x(+1.0, 1.0);
  view.up = {0.0, std::sin(0.21), std::cos(0.21)};
  view.forward = {1.0, 0.15, -0.05};
  return view;
}

// Refines a still view until the renderer goes idle; returns the final picture and the steps it drew.
Image converge(Renderer& renderer, const View& view, int* steps = nullptr) {
  int n = 0;
  while (renderer.refine(view, kWidth, kHeight)) {
    if (++n > 1000) ADD_FAILURE() << "refinement never converged";
    if (n > 1000) break;
  }
  if (steps) *steps = n;
  return renderer.read_pixels(kWidth, kHeight);
}

// The coarse level is flat per polygon (PLGT, or the mean of the polygon's vertices where the bundle has no
// PLGT, as here: write_bundle does not write it yet); patches follow the per-vertex gradient. Every byte of
// every frame in between moves one way only, from the coarse frame to the patch frame.
TEST_P(RefineImageTest, CoarseToPatchBlendIsMonotone) {
  TwoRooms scene;
  scene.light_gradient = true;
  scene.subdivisions = 4;
  auto bundle = open_two_rooms(scene, "blend");
  Renderer renderer(*bundle);
  renderer.set_refine_settings({.blend_steps = 10, .aa_samples = 1});
  renderer.set_moving_level(MovingLevel::Coarse);
  const View view = looking_along_x(+1.0);
  ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().stage, RefineStage::Moving);
  EXPECT_EQ(renderer.last_stats().patch_weight, 0.0f);
  std::vector<Image> frames{renderer.read_pixels(kWidth, kHeight)};
  int blend_frames = 0;
  while (renderer.refine(view, kWidth, kHeight)) {
    frames.push_back(renderer.read_pixels(kWidth, kHeight));
    blend_frames += renderer.last_stats().stage == RefineStage::Blending;
  }
  EXPECT_EQ(blend_frames, 10);
  const Image& coarse = frames.front();
  const Image& fine = frames.back();
  // B's far wall: its light rises with height; 8 pixels above the centre is still that wall.
  const std::uint8_t* c_mid = centre(coarse);
  const std::uint8_t* c_up = coarse.pixel(kWidth / 2, kHeight / 2 - 8);
  const std::uint8_t* f_mid = centre(fine);
  const std::uint8_t* f_up = fine.pixel(kWidth / 2, kHeight / 2 - 8);
  const glm::dvec3 mean = radiosity(scene, true, scene.wall_factor, 1, 1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(int(c_mid[k]), expected_byte(mean[k], scene.exposure), 2) << "coarse: the polygon's mean";
    EXPECT_EQ(c_mid[k], c_up[k]) << "coarse is flat over the polygon, channel " << k;
  }
  EXPECT_GT(int(f_up[1]), int(f_mid[1]) + 5) << "patches show the gradient";
  int changed = 0;
  for (std::size_t i = 0; i < fine.rgba.size(); ++i) {
    const bool up = fine.rgba[i] >= coarse.rgba[i];
    changed += fine.rgba[i] != coarse.rgba[i];
    for (std::size_t f = 1; f < frames.size(); ++f) {
      const int a = frames[f - 1].rgba[i], b = frames[f].rgba[i];
      ASSERT_TRUE(up ? b >= a : b <= a) << "frame " << f << ", byte " << i << ": " << a << " -> " << b;
    }
  }
  EXPECT_GT(changed, int(fine.rgba.size() / 8));
}

// Aliasing measure: mean absolute difference from a 64-sample picture, over pixels where that picture
// differs from the single-sample one (the edges). Must fall as samples grow: 1 > 4 > 16.
// The coarse form (CIDX) draws the moving frame with each polygon's fewest triangles: the same flat picture
// as the diced triangles give, in a fraction of the triangles; once still, the patches are the same frame.
TEST_P(RefineImageTest, CoarseFormDrawsTheSameMovingFrameInFewerTriangles) {
  TwoRooms scene;
  scene.light_gradient = true;
  scene.subdivisions = 6;
  auto diced = open_two_rooms(scene, "coarse_off");
  scene.coarse_form = true;
  auto coarse = open_two_rooms(scene, "coarse_on");
  ASSERT_FALSE(coarse->coarse_indices().empty());
  const View view = rolled_view();
  std::vector<Image> moving, still;
  std::vector<std::uint32_t> triangles;
  for (const auto* bundle : {diced.get(), coarse.get()}) {
    Renderer renderer(*bundle);
    renderer.set_refine_settings({.blend_steps = 2, .aa_samples = 1});
    renderer.set_moving_level(MovingLevel::Coarse);
    ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
    ASSERT_EQ(renderer.last_stats().patch_weight, 0.0f);
    triangles.push_back(renderer.last_stats().triangles_drawn);
    moving.push_back(renderer.read_pixels(kWidth, kHeight));
    still.push_back(converge(renderer, view));
  }
  EXPECT_EQ(triangles[1] * 36, triangles[0]) << "6 x 6 quads per rectangle against one";
  // Flat light per polygon: the two triangulations cover the same pixels with the same colour. Depth is
  // interpolated over different triangles, so where two polygons meet at a corner a pixel may go either
  // way; allow those few (the rooms' edges are a small fraction of the frame).
  std::size_t differing = 0;
  for (std::size_t i = 0; i < moving[0].rgba.size(); ++i) differing += moving[0].rgba[i] != moving[1].rgba[i];
  EXPECT_LE(differing, moving[0].rgba.size() / 1000) << differing << " bytes differ";
  EXPECT_EQ(still[0].rgba, still[1].rgba) << "patches do not use the coarse form";
}

// Samples are averaged as light, not as display bytes: white and black in equal weight resolve to the
// sRGB code of linear 0.5 (188), not to 128; equal samples come back unchanged (decode and encode agree).
TEST_P(RefineImageTest, AccumulationAveragesLinearLight) {
  constexpr int kSize = 8;
  auto fill = [](Framebuffer& target, float grey) {
    target.ensure_size(kSize, kSize);
    glBindFramebuffer(GL_FRAMEBUFFER, target.id());
    glClearColor(grey, grey, grey, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  };
  auto resolved = [](Accumulator& sum, Framebuffer& out) {
    out.ensure_size(kSize, kSize);
    sum.resolve(out.id());
    std::uint8_t rgba[4] = {};
    glBindFramebuffer(GL_FRAMEBUFFER, out.id());
    glReadPixels(kSize / 2, kSize / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return int(rgba[0]);
  };
  Framebuffer white, black, grey, out;
  fill(white, 1.0f);
  fill(black, 0.0f);
  fill(grey, 100.0f / 255.0f);
  Accumulator sum;
  sum.reset(kSize, kSize);
  sum.add(white.colour_texture(), 1.0f);
  sum.add(black.colour_texture(), 1.0f);
  EXPECT_NEAR(resolved(sum, out), 188, 1) << "linear 0.5 encodes to 188";
  sum.reset(kSize, kSize);
  sum.add(grey.colour_texture(), 0.25f);
  sum.add(grey.colour_texture(), 2.0f);
  EXPECT_NEAR(resolved(sum, out), 100, 1) << "a constant picture is a fixed point";
  sum.reset(kSize, kSize);
  sum.add(white.colour_texture(), 3.0f);  // weights: three quarters white
  sum.add(black.colour_texture(), 1.0f);
  EXPECT_NEAR(resolved(sum, out), 225, 1) << "linear 0.75 encodes to 225";
}

TEST_P(RefineImageTest, AccumulationLowersEdgeAliasing) {
  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "aliasing");
  Renderer renderer(*bundle);
  const View view = rolled_view();
  auto picture = [&](int samples) {
    renderer.set_refine_settings({.blend_steps = 0, .aa_samples = samples});
    return converge(renderer, view);
  };
  const Image reference = picture(64);
  const Image one = picture(1);
  std::vector<std::size_t> edge;
  for (std::size_t i = 0; i < one.rgba.size(); ++i)
    if (i % 4 != 3 && std::abs(int(one.rgba[i]) - int(reference.rgba[i])) > 2) edge.push_back(i);
  ASSERT_GT(edge.size(), 100u) << "the view must have slanted edges";
  auto measure = [&](const Image& image) {
    double sum = 0.0;
    for (std::size_t i : edge) sum += std::abs(int(image.rgba[i]) - int(reference.rgba[i]));
    return sum / double(edge.size());
  };
  const double e1 = measure(one), e4 = measure(picture(4)), e16 = measure(picture(16));
  std::cout << "[ aliasing ] mean error at edges: 1 sample " << e1 << ", 4: " << e4 << ", 16: " << e16
            << "\n";
  EXPECT_LT(e4, 0.7 * e1);
  EXPECT_LT(e16, 0.7 * e4);
  // Away from edges accumulation changes nothing: a flat wall stays its formula colour.
  const glm::dvec3 wall = radiosity(scene, true, scene.wall_factor, 1, 1);
  const Image sixteen = picture(16);
  EXPECT_EQ(renderer.last_stats().samples, 16);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(int(centre(sixteen)[k]), expected_byte(wall[k], scene.exposure), 2) << "channel " << k;
}

TEST_P(RefineImageTest, IdleRendererDrawsNothingUntilSomethingChanges) {
  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "idle");
  Renderer renderer(*bundle);
  // Diagonals in one frame however slow the machine, so the frames can be counted.
  renderer.set_refine_settings(
      {.blend_steps = 5, .aa_samples = 4, .samples_per_frame = 1, .diagonal_slice_ms = 0.0});
  renderer.set_moving_level(MovingLevel::Coarse);
  const View view = looking_along_x(+1.0);
  int steps = 0;
  const Image done = converge(renderer, view, &steps);
  EXPECT_EQ(steps, 1 + 5 + 1 + 4);  // moving frame, blend steps, diagonals, one sample per step
  const auto frames = renderer.last_stats().frames_drawn;
  for (int i = 0; i < 20; ++i) ASSERT_FALSE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().frames_drawn, frames) << "an idle renderer must not draw";
  EXPECT_EQ(renderer.last_stats().stage, RefineStage::Idle);
  EXPECT_EQ(renderer.read_pixels(kWidth, kHeight).rgba, done.rgba);

  // A dimmer change redraws (a plain patch frame, no coarse one; then diagonals and samples again), then
  // goes idle again.
  renderer.set_dimmers(std::vector<float>{0.5f, 1.0f});
  ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().stage, RefineStage::Relit);
  EXPECT_EQ(renderer.last_stats().patch_weight, 1.0f);
  ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().stage, RefineStage::Diagonals);
  (void)converge(renderer, view);
  EXPECT_FALSE(renderer.refine(view, kWidth, kHeight));
  // Setting the same levels again is not a change.
  renderer.set_dimmers(std::vector<float>{0.5f, 1.0f});
  EXPECT_FALSE(renderer.refine(view, kWidth, kHeight));
  // Moving draws a moving frame.
  View moved = view;
  moved.eye.x += 0.01;
  ASSERT_TRUE(renderer.refine(moved, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().stage, RefineStage::Moving);
}

// A wall drawn as one quad whose corners alternate 1.6 and 0.4 times the light: the bundle's diagonal joins
// the two bright corners, so its centre shows 1.6; the bilinear patch has the corners' mean, 1.0, there.
// Subdivision must bring the centre to the bilinear value; without it, the centre stays on the diagonal.
TEST_P(RefineImageTest, BilinearSubdivisionWhereTheTwistIsLarge) {
  TwoRooms scene;
  scene.light_twist = true;
  auto bundle = open_two_rooms(scene, "twist");
  const View view = looking_along_x(-1.0);  // A's outer wall, centred
  auto refined = [&](int depth, FrameStats* stats, bool map = false) {
    Renderer renderer(*bundle);
    renderer.set_map_overlay(map, 0.2f);  // in a corner, away from the wall's centre
    renderer.set_refine_settings({.blend_steps = 0, .aa_samples = 1, .subdivision_depth = depth});
    const Image image = converge(renderer, view);
    *stats = renderer.last_stats();
    return image;
  };
  FrameStats flat_stats, sub_stats;
  const Image flat = refined(0, &flat_stats);
  const Image sub = refined(4, &sub_stats);
  FrameStats map_stats;
  const Image with_map = refined(4, &map_stats, true);  // the map view shares the subdivision's shader
  EXPECT_EQ(flat_stats.quads_subdivided, 0u);
  EXPECT_GT(sub_stats.quads_subdivided, 0u);
  EXPECT_GT(sub_stats.subdivision_triangles, 2 * sub_stats.quads_subdivided);
  const glm::dvec3 diagonal = radiosity(scene, false, 1.6 * scene.wall_factor, 1, 1);
  const glm::dvec3 bilinear = radiosity(scene, false, 1.0 * scene.wall_factor, 1, 1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(int(centre(flat)[k]), expected_byte(diagonal[k], scene.exposure), 3)
        << "no subdivision, " << k;
    EXPECT_NEAR(int(centre(sub)[k]), expected_byte(bilinear[k], scene.exposure), 3) << "subdivided, " << k;
    EXPECT_EQ(centre(with_map)[k], centre(sub)[k]) << "subdivided with the map view on, " << k;
  }
}

// Sub-quads go with their unit: a still frame draws those of the units its list draws (the twist scene
// subdivides quads on several walls, some behind each view), and the picture equals the one that draws every
// unit and every sub-quad.
TEST_P(RefineImageTest, SubQuadsAreDrawnWithTheirUnitsOnly) {
  TwoRooms scene;
  scene.light_twist = true;
  auto bundle = open_two_rooms(scene, "twist_culled");
  Renderer culled(*bundle), every(*bundle);
  every.set_pvs_culling(false);
  every.set_frustum_culling(false);
  for (Renderer* r : {&culled, &every})
    r->set_refine_settings({.blend_steps = 0, .aa_samples = 1, .subdivision_depth = 4});
  for (const double sign : {-1.0, +1.0}) {
    const View view = looking_along_x(sign);
    const Image culled_image = converge(culled, view), every_image = converge(every, view);
    const FrameStats& c = culled.last_stats();
    ASSERT_GT(every.last_stats().subdivision_triangles, 0u);
    EXPECT_EQ(every.last_stats().subdivision_triangles_drawn, every.last_stats().subdivision_triangles);
    EXPECT_GT(c.subdivision_triangles_drawn, 0u) << "looking along " << sign;
    EXPECT_LT(c.subdivision_triangles_drawn, c.subdivision_triangles) << "looking along " << sign;
    EXPECT_EQ(culled_image.rgba, every_image.rgba) << "looking along " << sign;
  }
}

// A stop whose slice makes one unit a frame uploads each frame's sub-quads after the ones before (in the
// order made, not the sight's): the picture equals a stop that makes every unit in one frame, also after a
// dimmer change (every unit made again, the buffer gathered anew) and for another view.
TEST_P(RefineImageTest, SubQuadsMadeOverManySlicesDrawAsMadeInOne) {
  TwoRooms scene;
  scene.light_twist = true;
  auto bundle = open_two_rooms(scene, "twist_sliced");
  Renderer sliced(*bundle), at_once(*bundle);
  sliced.set_refine_settings(
      {.blend_steps = 0, .aa_samples = 1, .subdivision_depth = 4, .diagonal_slice_ms = 1e-9});
  at_once.set_refine_settings(
      {.blend_steps = 0, .aa_samples = 1, .subdivision_depth = 4, .diagonal_slice_ms = 0.0});
  const auto diagonal_frames = [](Renderer& renderer, const View& view, Image* image) {
    int frames = 0;
    for (int n = 0; renderer.refine(view, kWidth, kHeight) && n < 1000; ++n)
      frames += renderer.last_stats().stage == RefineStage::Diagonals;
    *image = renderer.read_pixels(kWidth, kHeight);
    return frames;
  };
  for (const double sign : {-1.0, +1.0}) {
    const View view = looking_along_x(sign, 1.0);
    for (const float dimmer : {1.0f, 0.4f}) {
      for (Renderer* r : {&sliced, &at_once}) r->set_dimmers(std::vector<float>{dimmer, 1.0f});
      Image sliced_image, at_once_image;
      const int sliced_frames = diagonal_frames(sliced, view, &sliced_image);
      EXPECT_EQ(diagonal_frames(at_once, view, &at_once_image), 1);
      EXPECT_GT(sliced_frames, 2) << "one unit a frame, looking along " << sign;
      ASSERT_GT(sliced.last_stats().subdivision_triangles_drawn, 0u);
      EXPECT_EQ(sliced.last_stats().subdivision_triangles_drawn,
                at_once.last_stats().subdivision_triangles_drawn);
      EXPECT_EQ(sliced_image.rgba, at_once_image.rgba) << "looking along " << sign << ", dimmer " << dimmer;
    }
  }
}

// Where subdivided quads meet quads that are not, the sub-quads' edge midpoints are T-junctions: in float,
// pixels along such an edge can fall between the triangles and show the clear colour. The room is closed
// (ambient light everywhere), so a black pixel is a crack.
TEST_P(RefineImageTest, SubdivisionLeavesNoCracks) {
  TwoRooms scene;
  scene.light_twist_half = true;
  scene.subdivisions = 8;
  auto bundle = open_two_rooms(scene, "twist_half");
  View view = looking_along_x(-1.0, 1.0);
  view.forward = {-1.0, 0.31, 0.17};  // oblique: edges off the pixel grid
  view.eye.x = 3.3;
  Renderer renderer(*bundle);
  renderer.set_refine_settings({.blend_steps = 0, .aa_samples = 1, .subdivision_depth = 3});
  const Image image = converge(renderer, view);
  ASSERT_GT(renderer.last_stats().quads_subdivided, 0u);
  int black = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    black += image.rgba[i] == 0 && image.rgba[i + 1] == 0 && image.rgba[i + 2] == 0;
  EXPECT_EQ(black, 0) << "pixels showing the clear colour through cracks";
}

// The Reduced moving level draws at half size and scales up: a flat wall keeps its colour, the frame its
// size, and the next still frame is full resolution again.
// The first frame down each drawing path pays llvmpipe's JIT (the half-resolution blit 40-90 ms): refine()
// draws each moving level once off the record at a new frame size, before the frame it shows.
TEST_P(RefineImageTest, EachNewFrameSizeWarmsTheMovingLevelsOffTheRecord) {
  auto bundle = open_two_rooms(TwoRooms{}, "warm_up");
  Renderer renderer(*bundle);
  ASSERT_TRUE(renderer.refine(looking_along_x(+1.0), kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().warm_up_frames, std::uint64_t(kMovingLevels));
  EXPECT_EQ(renderer.last_stats().frames_drawn, 1u) << "the warm-up frames are not counted as drawn";
  const Image shown = renderer.read_pixels(kWidth, kHeight);
  ASSERT_TRUE(renderer.refine(looking_along_x(-1.0), kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().warm_up_frames, std::uint64_t(kMovingLevels)) << "same size: once";
  ASSERT_TRUE(renderer.refine(looking_along_x(+1.0), kWidth / 2, kHeight / 2));
  EXPECT_EQ(renderer.last_stats().warm_up_frames, std::uint64_t(2 * kMovingLevels)) << "a new size";
  // What was shown is the frame asked for (nothing known yet: patches, full size), not the last warm-up
  // frame (half resolution): the same bytes as a plain draw of that view.
  Renderer fresh(*bundle);
  fresh.draw(looking_along_x(+1.0), kWidth, kHeight);
  EXPECT_EQ(shown.rgba, fresh.read_pixels(kWidth, kHeight).rgba);
}

TEST_P(RefineImageTest, ReducedMovingLevelIsHalfResolution) {
  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "reduced");
  Renderer renderer(*bundle);
  renderer.set_refine_settings({.blend_steps = 2, .aa_samples = 1});
  renderer.set_moving_level(MovingLevel::Reduced);
  const View view = looking_along_x(-1.0);
  ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().resolution, 0.5f);
  const Image moving = renderer.read_pixels(kWidth, kHeight);
  const glm::dvec3 wall = radiosity(scene, false, scene.wall_factor, 1, 1);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(int(centre(moving)[k]), expected_byte(wall[k], scene.exposure), 2) << "channel " << k;
  ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
  EXPECT_EQ(renderer.last_stats().resolution, 1.0f);
}

INSTANTIATE_TEST_SUITE_P(Headless, RefineImageTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace refine_image_test
}  // namespace walk::render::test
