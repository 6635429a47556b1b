#include <glad/gl.h>
// After glad, so the EGL headers do not pull in a second set of GL declarations.
#include <cstdio>
#include <cstring>

#include "model/error.hpp"
#include "render/backend/egl_common.hpp"

namespace walk::render::detail {

std::string egl_error(const char* backend, const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(eglGetError()));
  return std::string(backend) + ": " + what + " failed (EGL error " + code + ")";
}

bool has_egl_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

EGLContext create_gl33_core_context(EGLDisplay display, EGLConfig config, const char* backend) {
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            3,
                            EGL_CONTEXT_MINOR_VERSION,
                            3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_NONE};
  const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
  if (context == EGL_NO_CONTEXT) throw Error(egl_error(backend, "eglCreateContext for GL 3.3 core"));
  return context;
}

}  // namespace walk::render::detail
