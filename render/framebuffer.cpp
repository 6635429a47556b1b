#include "render/framebuffer.hpp"

#include <string>

#include "model/error.hpp"

namespace walk::render {

Framebuffer::~Framebuffer() {
  release();
}

void Framebuffer::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (colour_) glDeleteTextures(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  fbo_ = colour_ = depth_ = 0;
  width_ = height_ = 0;
}

void Framebuffer::ensure_size(int width, int height) {
  if (fbo_ && width == width_ && height == height_) return;
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width <= 0 || height <= 0 || width > max_size || height > max_size)
    throw Error("frame size " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside what this GL supports (1.." + std::to_string(max_size) + " per side)");
  release();
  // A texture rather than a renderbuffer: accumulation (anti-aliasing) reads each jittered frame back in.
  glGenTextures(1, &colour_);
  glBindTexture(GL_TEXTURE_2D, colour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    release();
    throw Error("offscreen framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                " (RGBA8 + depth24) is incomplete: status " + std::to_string(status));
  }
  width_ = width;
  height_ = height;
}

}  // namespace walk::render
