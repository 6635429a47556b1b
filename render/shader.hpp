#pragma once
// A linked GLSL program; compile and link failures throw walk::Error with the driver's log.
#include <glad/gl.h>

namespace walk::render {

class ShaderProgram {
 public:
  ShaderProgram(const char* name, const char* vertex_source, const char* fragment_source);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  [[nodiscard]] GLuint id() const { return program_; }
  // Location of a uniform the shader must use; throws when the linker removed or never had it.
  [[nodiscard]] GLint uniform(const char* name) const;

 private:
  const char* name_;
  GLuint program_ = 0;
};

}  // namespace walk::render
