#include "render/accumulator.hpp"

#include <array>
#include <cmath>
#include <string>

#include "model/error.hpp"
#include "render/gl_check.hpp"
#include "render/tonemap.hpp"

namespace walk::render {
namespace {

// One triangle covering the viewport, from gl_VertexID alone (core GL still wants a VAO bound).
const char* const kFullScreenVertex = R"glsl(#version 330 core
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)glsl";

// Samples arrive as display (sRGB) bytes; they are summed as linear light, which is what a pixel's area
// integrates, and encoded again at the resolve. Averaging the bytes instead darkens every edge: half white
// over black would give 128 where the light says 188. Decoding by table: exact for 8-bit input, no pow().
const char* const kAddFragment = R"glsl(#version 330 core
uniform sampler2D u_source;
uniform float u_weight;
uniform float u_decode[256];
out vec4 o_sum;
void main() {
  ivec3 code = ivec3(round(texelFetch(u_source, ivec2(gl_FragCoord.xy), 0).rgb * 255.0));
  vec3 linear = vec3(u_decode[code.r], u_decode[code.g], u_decode[code.b]);
  o_sum = vec4(linear * u_weight, u_weight);
}
)glsl";

const std::string kResolveFragment = std::string(R"glsl(#version 330 core
uniform sampler2D u_source;
out vec4 o_colour;
)glsl") + kSrgbEncodeGlsl + R"glsl(
void main() {
  vec4 s = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0);
  o_colour = vec4(s.a > 0.0 ? srgb_encode(s.rgb / s.a) : vec3(0.0), 1.0);
}
)glsl";

}  // namespace

Accumulator::Accumulator()
    : add_program_("accumulate", kFullScreenVertex, kAddFragment),
      resolve_program_("resolve", kFullScreenVertex, kResolveFragment.c_str()) {
  u_add_source_ = add_program_.uniform("u_source");
  u_add_weight_ = add_program_.uniform("u_weight");
  const auto decode = srgb_decode_table();
  glUseProgram(add_program_.id());
  glUniform1fv(glGetUniformLocation(add_program_.id(), "u_decode[0]"), 256, decode.data());
  glUseProgram(0);
  u_resolve_source_ = resolve_program_.uniform("u_source");
  glGenVertexArrays(1, &vao_);
}

Accumulator::~Accumulator() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (texture_) glDeleteTextures(1, &texture_);
  glDeleteVertexArrays(1, &vao_);
}

void Accumulator::reset(int width, int height) {
  if (!fbo_ || width != width_ || height != height_) {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (texture_) glDeleteTextures(1, &texture_);
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw Error("accumulation buffer " + std::to_string(width) + "x" + std::to_string(height) +
                  " (RGBA32F) is incomplete: status " + std::to_string(status));
    width_ = width;
    height_ = height;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  samples_ = 0;
  check_gl("clearing the accumulation buffer");
}

void Accumulator::add(GLuint colour, float weight) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glUseProgram(add_program_.id());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, colour);
  glUniform1i(u_add_source_, 0);
  glUniform1f(u_add_weight_, weight);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  ++samples_;
  check_gl("accumulating a sample");
}

void Accumulator::resolve(GLuint target_fbo) {
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(resolve_program_.id());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glUniform1i(u_resolve_source_, 0);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("resolving the accumulation buffer");
}

}  // namespace walk::render
