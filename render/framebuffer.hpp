#pragma once
// The renderer's own target: an RGBA8 colour texture and a 24-bit depth renderbuffer. Every backend draws
// here, so read_pixels is the same code whether or not a window exists.
#include <glad/gl.h>

namespace walk::render {

class Framebuffer {
 public:
  Framebuffer() = default;
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // (Re)allocates when the size changes; throws walk::Error when the driver refuses the attachments.
  void ensure_size(int width, int height);
  [[nodiscard]] GLuint id() const { return fbo_; }
  [[nodiscard]] GLuint colour_texture() const { return colour_; }
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

 private:
  void release();
  GLuint fbo_ = 0;
  GLuint colour_ = 0;
  GLuint depth_ = 0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace walk::render
