#pragma once
// What the EGL backends (headless EGL and EGL on GBM) share: error text and the GL 3.3 core context.
// Include after glad/gl.h, like the EGL headers themselves.
#include <EGL/egl.h>

#include <string>

namespace walk::render::detail {

// "<backend>: <what> failed (EGL error 0x3003)", with eglGetError's code.
[[nodiscard]] std::string egl_error(const char* backend, const char* what);

// Whether a space-separated EGL extension list holds `name` as a whole word.
[[nodiscard]] bool has_egl_extension(const char* list, const char* name);

// A desktop OpenGL 3.3 core context on `display` with `config` (EGL_NO_CONFIG_KHR where the display allows
// it); throws walk::Error naming the backend when the driver refuses.
[[nodiscard]] EGLContext create_gl33_core_context(EGLDisplay display, EGLConfig config, const char* backend);

}  // namespace walk::render::detail
