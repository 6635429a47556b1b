// The compact light form drawn (issue 26, item 5): circuits the compiler kept compact are drawn from the
// paper's 8-bit form, the others from LGHT, and the picture matches the full form's within the display's
// own steps while the light takes a fraction of the memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "compiler/radiosity/compact_light.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace compact_light_image_test {  // named, not anonymous: the suite compiles as unity batches

// The two rooms with a light gradient, circuit 1 a warm lamp (red tripled, blue halved): where both light,
// one colour per vertex cannot hold both tints, so the compiler's choice keeps circuit 0 compact only.
model::BundleContents warm_and_white() {
  TwoRooms scene;
  scene.subdivisions = 4;
  scene.light_gradient = true;
  model::BundleContents c = make_two_rooms(scene);
  const std::size_t circuits = c.circuits.size();
  for (model::LightEntry& e : c.light.entries)
    if (e.circuit == 1) {
      e.rgb[0] *= 3.0f;
      e.rgb[2] *= 0.5f;
    }
  const auto chosen = compiler::choose_light_forms(c.light.view(), c.vertices.size(), circuits);
  c.compact_colour = chosen.colour;
  c.compact_intensity = chosen.intensity;
  for (std::size_t i = 0; i < circuits; ++i) {
    c.circuits[i].compact_scale = chosen.scale[i];
    c.circuits[i].light_form = chosen.compact[i] ? model::LightForm::Compact : model::LightForm::Full;
    c.circuits[i].compact_error = float(chosen.circuit_rms[i]);
  }
  return c;
}

// Looking from room A into B through the opening: both rooms, both circuits in view.
View both_rooms() {
  View view = looking_along_x(+1.0, 1.0);
  view.forward = {1.0, 0.15, -0.2};
  return view;
}

class CompactLightImageTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override { backend_ = headless(GetParam()); }
  Image frame(Renderer& renderer, std::vector<float> levels) {
    renderer.set_dimmers(levels);
    renderer.draw(both_rooms(), kWidth, kHeight);
    return renderer.read_pixels(kWidth, kHeight);
  }
  std::unique_ptr<Backend> backend_;
};

// Largest difference of one channel between two frames, in 8-bit steps.
int largest_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
  return worst;
}

TEST_P(CompactLightImageTest, CompiledFormsMatchTheFullFormWithinTheDisplaysSteps) {
  const auto contents = warm_and_white();
  ASSERT_EQ(contents.circuits[0].light_form, model::LightForm::Compact);
  ASSERT_EQ(contents.circuits[1].light_form, model::LightForm::Full);  // the warm lamp
  const auto bundle = open_bundle(contents, "compact_forms");
  const DisplayLight as_compiled(*bundle, DisplayLightForm::AsCompiled),
      full(*bundle, DisplayLightForm::Full);
  EXPECT_EQ(as_compiled.compact_circuits(), std::vector<std::uint32_t>{0});
  EXPECT_EQ(as_compiled.full_circuits(), std::vector<std::uint32_t>{1});
  EXPECT_TRUE(full.compact_circuits().empty());
  // Both lamps reach every vertex: one full entry (16 bytes) and one compact (4 bytes, plus the vertex's
  // shared colour) in place of two full ones, beside each vertex's 8-byte first entries.
  const std::size_t vertices = bundle->vertices().size();
  EXPECT_EQ(full.full_entries().size(), 2 * vertices);
  EXPECT_EQ(as_compiled.full_entries().size(), vertices);
  EXPECT_EQ(as_compiled.compact_entries().size(), vertices);
  EXPECT_EQ(as_compiled.gpu_bytes(), vertices * (8 + 16 + 4 + 4));
  EXPECT_EQ(full.gpu_bytes(), vertices * (8 + 2 * 16));
  // The sparse entries mix exactly as the dense arrays would.
  const std::vector<float> levels{0.7f, 0.3f};
  const auto light = bundle->light().dense(2);
  for (std::size_t v = 0; v < vertices; ++v) {
    glm::vec3 dense(0.0f);
    for (std::size_t c = 0; c < 2; ++c)
      dense += levels[c] *
               glm::vec3(light[(v * 2 + c) * 3], light[(v * 2 + c) * 3 + 1], light[(v * 2 + c) * 3 + 2]);
    const glm::vec3 mixed = full.mixed(v, levels);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(mixed[k], dense[k]) << "vertex " << v;
    }
  }

  Renderer compiled_renderer(*bundle), full_renderer(*bundle, DisplayLightForm::Full);
  int worst = 0;
  for (const std::vector<float>& levels :
       {std::vector<float>{1.0f, 1.0f}, {1.0f, 0.0f}, {0.5f, 1.0f}, {0.0f, 1.0f}}) {
    const Image a = frame(compiled_renderer, levels), b = frame(full_renderer, levels);
    const int d = largest_difference(a, b);
    // Circuit 0's compact error (well under kCompactErrorLimit here) plus a step of rounding each.
    EXPECT_LE(d, 3) << "levels " << levels[0] << ", " << levels[1];
    if (levels[0] == 0.0f) {
      EXPECT_EQ(d, 0) << "only the full circuit is on: nothing compact is drawn";
    }
    worst = std::max(worst, d);
  }
  std::cout << "[ compact  ] circuit 0 compact (" << 100.0 * contents.circuits[0].compact_error
            << "% RMS), circuit 1 full (" << 100.0 * contents.circuits[1].compact_error
            << "% RMS if compact); largest pixel difference " << worst << " steps\n";
}

// The compact path is really what is drawn: doubling circuit 0's scale brightens its light on screen, and
// the full form ignores it.
TEST_P(CompactLightImageTest, TheShaderReadsTheCompactForm) {
  auto contents = warm_and_white();
  const auto bundle = open_bundle(contents, "compact_scale");
  contents.circuits[0].compact_scale *= 2.0f;
  const auto doubled = open_bundle(contents, "compact_scale_doubled");
  Renderer a(*bundle), b(*doubled), full_a(*bundle, DisplayLightForm::Full),
      full_b(*doubled, DisplayLightForm::Full);
  const Image fa = frame(a, {1.0f, 0.0f}), fb = frame(b, {1.0f, 0.0f});
  std::size_t brighter = 0, channels = 0;
  for (std::size_t i = 0; i < fa.rgba.size(); ++i) {
    if (i % 4 == 3 || fa.rgba[i] >= 250) continue;
    ++channels;
    brighter += fb.rgba[i] > fa.rgba[i] + 5;
  }
  EXPECT_GT(brighter, channels / 2) << brighter << " of " << channels;
  EXPECT_EQ(largest_difference(frame(full_a, {1.0f, 0.0f}), frame(full_b, {1.0f, 0.0f})), 0);
}

// The coarse level mixes each polygon's own circuits in the vertex shader, as the patches do, so a dimmer
// turned while walking is one uniform upload. Its light holds every circuit as floats while the shader's
// level of a compact circuit carries the circuit's scale: the compact circuit's polygon light is stored
// divided by it, and both forms draw the same coarse frame.
TEST_P(CompactLightImageTest, TheCoarseLevelMixesInTheShaderWhateverTheForm) {
  const auto bundle = open_bundle(warm_and_white(), "compact_coarse");
  const DisplayLight as_compiled(*bundle, DisplayLightForm::AsCompiled),
      full(*bundle, DisplayLightForm::Full);
  ASSERT_FALSE(as_compiled.compact_circuits().empty());
  Renderer compiled_renderer(*bundle), full_renderer(*bundle, DisplayLightForm::Full);
  auto coarse = [&](Renderer& renderer, const std::vector<float>& levels) {
    renderer.set_dimmers(levels);
    renderer.draw(both_rooms(), kWidth, kHeight, DrawOptions{.patch_weight = 0.0f});
    return renderer.read_pixels(kWidth, kHeight);
  };
  for (const std::vector<float>& levels : {std::vector<float>{1.0f, 1.0f}, {0.25f, 1.0f}, {1.0f, 0.0f}}) {
    for (std::size_t p = 0; p < bundle->polygons().size(); ++p) {
      const glm::vec3 a = as_compiled.polygon_mixed(p, levels), b = full.polygon_mixed(p, levels);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a[k], b[k], 1e-5f * std::max(1.0f, b[k])) << "polygon " << p;  // float division
      }
    }
    EXPECT_LE(largest_difference(coarse(compiled_renderer, levels), coarse(full_renderer, levels)), 1);
  }
  // And the levels reach it: circuit 0 off darkens the coarse frame.
  EXPECT_GT(
      largest_difference(coarse(compiled_renderer, {1.0f, 1.0f}), coarse(compiled_renderer, {0.0f, 1.0f})),
      5);
}

INSTANTIATE_TEST_SUITE_P(Headless, CompactLightImageTest,
                         ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace compact_light_image_test
}  // namespace walk::render::test
