#include "render/shader.hpp"

#include <string>

#include "model/error.hpp"

namespace walk::render {
namespace {

GLuint compile(GLenum stage, const char* source, const char* name) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
  glDeleteShader(shader);
  throw Error(std::string("shader '") + name + "': " + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
              " stage does not compile:\n" + log.c_str());
}

}  // namespace

ShaderProgram::ShaderProgram(const char* name, const char* vertex_source, const char* fragment_source)
    : name_(name) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertex_source, name);
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, fragment_source, name);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);  // flagged: freed with the program
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program_, GLsizei(log.size()), nullptr, log.data());
    glDeleteProgram(program_);
    throw Error(std::string("shader '") + name + "' does not link:\n" + log.c_str());
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_) glDeleteProgram(program_);
}

GLint ShaderProgram::uniform(const char* uniform_name) const {
  const GLint location = glGetUniformLocation(program_, uniform_name);
  if (location < 0)
    throw Error(std::string("shader '") + name_ + "' has no active uniform '" + uniform_name + "'");
  return location;
}

}  // namespace walk::render
