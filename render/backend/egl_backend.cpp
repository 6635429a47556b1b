// EGL without any window system: Mesa's surfaceless platform, else the first EGL device. There is no
// surface at all; the renderer draws into its own FBO, which is why read_pixels works the same everywhere.
#include <glad/gl.h>
// After glad, so the EGL headers do not pull in a second set of GL declarations.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

#include "model/error.hpp"
#include "render/backend/backend_factories.hpp"
#include "render/backend/egl_common.hpp"
#include "render/gl_loader.hpp"

namespace walk::render::detail {
namespace {

std::string egl_error(const char* what) {
  return detail::egl_error("egl", what);
}

bool has_extension(const char* list, const char* name) {
  return has_egl_extension(list, name);
}

// Surfaceless Mesa first (no device files needed), then the first enumerated device.
EGLDisplay open_display(std::string& platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display || !has_extension(client, "EGL_EXT_platform_base"))
    throw Error("egl: EGL_EXT_platform_base is not available, so no headless display can be opened");
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
      platform = "surfaceless";
      return display;
    }
  }
  if (has_extension(client, "EGL_EXT_platform_device")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT device = nullptr;
    EGLint count = 0;
    if (query_devices && query_devices(1, &device, &count) && count > 0) {
      EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
      if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
        platform = "device";
        return display;
      }
    }
  }
  throw Error(
      egl_error("opening a surfaceless or device display (EGL_MESA_platform_surfaceless, "
                "EGL_EXT_platform_device)"));
}

class EGLBackend final : public Backend {
 public:
  explicit EGLBackend(const BackendOptions& options) : width_(options.width), height_(options.height) {
    display_ = open_display(platform_);
    try {
      if (!eglBindAPI(EGL_OPENGL_API)) throw Error(egl_error("eglBindAPI(EGL_OPENGL_API)"));
      const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
      if (!has_extension(extensions, "EGL_KHR_surfaceless_context"))
        throw Error(
            "egl: EGL_KHR_surfaceless_context is missing, so a context cannot be current without a surface");
      EGLConfig config = EGL_NO_CONFIG_KHR;
      if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0)
          throw Error(egl_error("eglChooseConfig for desktop OpenGL"));
      }
      context_ = create_gl33_core_context(display_, config, "egl");
      make_current();
    } catch (...) {
      release();
      throw;
    }
  }
  ~EGLBackend() override { release(); }

  const char* name() const override { return "egl"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void make_current() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw Error(egl_error("eglMakeCurrent without a surface"));
    load_gl(reinterpret_cast<GLADloadfunc>(eglGetProcAddress), "egl");
  }

 private:
  void release() {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
    display_ = EGL_NO_DISPLAY;
  }

  int width_;
  int height_;
  std::string platform_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Backend> make_egl_backend(const BackendOptions& options) {
  return std::make_unique<EGLBackend>(options);
}

}  // namespace walk::render::detail
