#include "render/gl_check.hpp"

#include <glad/gl.h>

#include <cstdio>
#include <string>

#include "model/error.hpp"

namespace walk::render {

void throw_on_gl_error(const char* where) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
  throw Error(std::string("GL error ") + code + " after " + where);
}

}  // namespace walk::render
