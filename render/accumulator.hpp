#pragma once
// Accumulation buffer for anti-aliasing: each jittered frame (display values, RGBA8) is decoded to linear
// light and added into an RGBA32F target times its filter weight, with the weight summed in alpha; resolving
// divides by it and encodes to sRGB again. Needs a current
// GL context for its whole life.
#include <glad/gl.h>

#include "render/shader.hpp"

namespace walk::render {

class Accumulator {
 public:
  Accumulator();
  ~Accumulator();
  Accumulator(const Accumulator&) = delete;
  Accumulator& operator=(const Accumulator&) = delete;

  // Empties the sum, (re)allocating at this size.
  void reset(int width, int height);
  // Adds `colour` (an RGBA8 texture of the same size) times `weight`.
  void add(GLuint colour, float weight);
  // Writes the weighted mean into `target_fbo`'s colour, opaque.
  void resolve(GLuint target_fbo);
  [[nodiscard]] int samples() const { return samples_; }

 private:
  ShaderProgram add_program_;
  ShaderProgram resolve_program_;
  GLint u_add_source_ = -1, u_add_weight_ = -1, u_resolve_source_ = -1;
  GLuint vao_ = 0, fbo_ = 0, texture_ = 0;
  int width_ = 0, height_ = 0, samples_ = 0;
};

}  // namespace walk::render
