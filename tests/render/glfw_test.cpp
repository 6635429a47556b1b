// The window backend, where a display exists (CI runs this binary under xvfb-run too): the frame drawn in
// the renderer's FBO reaches the window's back buffer unchanged.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace glfw_test {  // named, not anonymous: the suite compiles as unity batches

TEST(GlfwBackend, BlitsTheFrameToTheWindow) {
#if !WALK_WITH_GLFW
  GTEST_SKIP() << "built without GLFW";
#else
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) GTEST_SKIP() << "no DISPLAY: run under xvfb-run to test the window backend";
  BackendOptions options;
  options.kind = BackendKind::GLFW;
  options.width = kWidth;
  options.height = kHeight;
  auto backend = Backend::create(options);
  backend->make_current();
  EXPECT_TRUE(backend->has_window());
  ASSERT_EQ(backend->width(), kWidth);
  ASSERT_EQ(backend->height(), kHeight);

  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "glfw");
  Renderer renderer(*bundle);
  renderer.set_present_to_window(backend->has_window());
  renderer.draw(looking_along_x(+1.0), kWidth, kHeight);
  const Image frame = renderer.read_pixels(kWidth, kHeight);

  std::vector<std::uint8_t> window(frame.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, window.data());
  // The window's rows are bottom up; compare the centre and a corner row by row.
  for (int y : {0, kHeight / 2, kHeight - 1})
    for (int x : {0, kWidth / 2, kWidth - 1})
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(window[(std::size_t(kHeight - 1 - y) * kWidth + x) * 4 + k], frame.pixel(x, y)[k])
            << "x " << x << " y " << y << " channel " << k;
  backend->present();
  backend->poll_events();
  EXPECT_FALSE(backend->close_requested());
#endif
}

// Stereo eyes or screens of one spanning output: several renderers present into their own part of one
// window; and quad-buffered stereo that the display cannot show comes up as a mono window, saying so.
TEST(GlfwBackend, RenderersPresentIntoTheirOwnRegionsAndStereoFallsBackToMono) {
#if !WALK_WITH_GLFW
  GTEST_SKIP() << "built without GLFW";
#else
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) GTEST_SKIP() << "no DISPLAY: run under xvfb-run to test the window backend";
  BackendOptions options;
  options.kind = BackendKind::GLFW;
  options.width = 2 * kWidth;
  options.height = kHeight;
  options.stereo = true;  // Xvfb offers no quad-buffered visual
  auto backend = Backend::create(options);
  backend->make_current();
  ASSERT_TRUE(backend->has_window());
  EXPECT_FALSE(backend->stereo());

  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "glfw_regions");
  Renderer left(*bundle), right(*bundle);
  left.set_present_to_window(true);
  right.set_present_to_window(true);
  right.set_present_region({kWidth, 0, WindowBuffer::Back});
  left.draw(looking_along_x(-1.0), kWidth, kHeight);   // A's outer wall
  right.draw(looking_along_x(+1.0), kWidth, kHeight);  // through the opening
  std::vector<std::uint8_t> window(std::size_t(2 * kWidth) * kHeight * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, 2 * kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, window.data());
  const Image a = left.read_pixels(kWidth, kHeight), b = right.read_pixels(kWidth, kHeight);
  for (int y : {0, kHeight / 2, kHeight - 1})
    for (int x : {0, kWidth / 2, kWidth - 1})
      for (int k = 0; k < 3; ++k) {
        const std::size_t row = std::size_t(kHeight - 1 - y) * 2 * kWidth;
        EXPECT_EQ(window[(row + x) * 4 + k], a.pixel(x, y)[k]) << "left x " << x << " y " << y;
        EXPECT_EQ(window[(row + kWidth + x) * 4 + k], b.pixel(x, y)[k]) << "right x " << x << " y " << y;
      }
#endif
}

}  // namespace glfw_test
}  // namespace walk::render::test
