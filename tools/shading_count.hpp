#pragma once
// Vertices and fragments the GL shaded between each begin() and end(), summed, from
// GL_ARB_pipeline_statistics_query (llvmpipe has it): on a software rasterizer the frame time follows the
// fragments, so the bench prints them beside the times. Counts nothing where the extension is missing.
#include <glad/gl.h>

#include <array>
#include <cstdint>

namespace walk::tools {

class ShadingCount {
 public:
  ShadingCount() {
    if (available()) glGenQueries(GLsizei(queries_.size()), queries_.data());
  }
  ~ShadingCount() {
    if (available()) glDeleteQueries(GLsizei(queries_.size()), queries_.data());
  }
  ShadingCount(const ShadingCount&) = delete;
  ShadingCount& operator=(const ShadingCount&) = delete;

  [[nodiscard]] static bool available() { return GLAD_GL_ARB_pipeline_statistics_query != 0; }

  void begin() {
    if (!available()) return;
    glBeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, queries_[0]);
    glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, queries_[1]);
  }
  void end() {
    if (!available()) return;
    glEndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    GLuint64 v = 0, f = 0;
    glGetQueryObjectui64v(queries_[0], GL_QUERY_RESULT, &v);
    glGetQueryObjectui64v(queries_[1], GL_QUERY_RESULT, &f);
    vertices += v;
    fragments += f;
  }

  std::uint64_t vertices = 0, fragments = 0;  // over every begin() .. end()

 private:
  std::array<GLuint, 2> queries_{};
};

}  // namespace walk::tools
