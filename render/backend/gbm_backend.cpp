// EGL on GBM/KMS: draws straight to a display connected to the GPU, with no X11, Wayland or compositor (a
// kiosk that boots into walkd). Opens a DRM card, takes its first connected connector at its preferred
// mode, renders through an EGL window surface on a GBM surface and shows each frame with a page flip.
// Needs DRM master on the card (no other display server running) and read/write access to /dev/dri/cardN.
#include <glad/gl.h>
// After glad, so the EGL headers do not pull in a second set of GL declarations.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fcntl.h>
#include <gbm.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "model/error.hpp"
#include "render/backend/backend_factories.hpp"
#include "render/backend/egl_common.hpp"
#include "render/gl_loader.hpp"

namespace walk::render::detail {
namespace {

std::string egl_error(const char* what) {
  return detail::egl_error("gbm", what);
}

// The first card in /dev/dri, or the one configured; a clear error when there is none (containers, CI).
std::string find_card(const std::string& configured) {
  if (!configured.empty()) return configured;
  std::error_code ec;
  if (!std::filesystem::is_directory("/dev/dri", ec))
    throw Error(
        "gbm: /dev/dri does not exist: this machine has no DRM display device (use egl or osmesa "
        "headless, or glfw with a display server)");
  for (int i = 0; i < 16; ++i) {
    const std::string path = "/dev/dri/card" + std::to_string(i);
    if (std::filesystem::exists(path, ec)) return path;
  }
  throw Error("gbm: no /dev/dri/card* device found");
}

class GBMBackend final : public Backend {
 public:
  explicit GBMBackend(const BackendOptions& options) {
    const std::string card = find_card(options.drm_device);
    fd_ = ::open(card.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0) throw Error("gbm: cannot open " + card + ": " + std::strerror(errno));
    try {
      choose_output(card, options.monitor);
      gbm_ = gbm_create_device(fd_);
      if (!gbm_) throw Error("gbm: gbm_create_device on " + card + " failed");
      surface_ = gbm_surface_create(gbm_, width_, height_, GBM_FORMAT_XRGB8888,
                                    GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
      if (!surface_)
        throw Error("gbm: gbm_surface_create " + std::to_string(width_) + "x" + std::to_string(height_));
      auto get_platform_display =
          reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
      if (!get_platform_display) throw Error("gbm: eglGetPlatformDisplayEXT is not available");
      display_ = get_platform_display(EGL_PLATFORM_GBM_KHR, gbm_, nullptr);
      if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr))
        throw Error(egl_error("opening the GBM EGL display"));
      if (!eglBindAPI(EGL_OPENGL_API)) throw Error(egl_error("eglBindAPI(EGL_OPENGL_API)"));
      const EGLConfig config = choose_config();
      context_ = create_gl33_core_context(display_, config, "gbm");
      egl_surface_ =
          eglCreateWindowSurface(display_, config, reinterpret_cast<EGLNativeWindowType>(surface_), nullptr);
      if (egl_surface_ == EGL_NO_SURFACE) throw Error(egl_error("eglCreateWindowSurface on the GBM surface"));
      make_current();
    } catch (...) {
      release();
      throw;
    }
  }
  ~GBMBackend() override { release(); }

  const char* name() const override { return "gbm"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool has_window() const override { return true; }
  void make_current() override {
    if (!eglMakeCurrent(display_, egl_surface_, egl_surface_, context_))
      throw Error(egl_error("eglMakeCurrent"));
    load_gl(reinterpret_cast<GLADloadfunc>(eglGetProcAddress), "gbm");
  }

  // Swap, then scan the new front buffer out: the first frame sets the mode, later ones page-flip and wait
  // for the flip (vsync), then the previous buffer goes back to GBM.
  void present() override {
    eglSwapBuffers(display_, egl_surface_);
    gbm_bo* bo = gbm_surface_lock_front_buffer(surface_);
    if (!bo) throw Error("gbm: no front buffer after eglSwapBuffers");
    std::uint32_t fb = 0;
    if (drmModeAddFB(fd_, std::uint32_t(width_), std::uint32_t(height_), 24, 32, gbm_bo_get_stride(bo),
                     gbm_bo_get_handle(bo).u32, &fb) != 0)
      throw Error(std::string("gbm: drmModeAddFB: ") + std::strerror(errno));
    if (!previous_bo_) {
      if (drmModeSetCrtc(fd_, crtc_, fb, 0, 0, &connector_, 1, &mode_) != 0)
        throw Error(std::string("gbm: drmModeSetCrtc (is another display server holding DRM master?): ") +
                    std::strerror(errno));
    } else {
      bool flipped = false;
      if (drmModePageFlip(fd_, crtc_, fb, DRM_MODE_PAGE_FLIP_EVENT, &flipped) == 0) {
        drmEventContext events{};
        events.version = 2;
        events.page_flip_handler = [](int, unsigned, unsigned, unsigned, void* data) {
          *static_cast<bool*>(data) = true;
        };
        while (!flipped && drmHandleEvent(fd_, &events) == 0) {
        }
      }
      drmModeRmFB(fd_, previous_fb_);
      gbm_surface_release_buffer(surface_, previous_bo_);
    }
    previous_bo_ = bo;
    previous_fb_ = fb;
  }

 private:
  // The `monitor`-th connected connector, its preferred (else first) mode, and a CRTC its encoder can drive.
  void choose_output(const std::string& card, int monitor) {
    drmModeRes* res = drmModeGetResources(fd_);
    if (!res) throw Error("gbm: " + card + " is not a KMS display device (drmModeGetResources failed)");
    int seen = 0;
    for (int i = 0; i < res->count_connectors && !crtc_; ++i) {
      drmModeConnector* c = drmModeGetConnector(fd_, res->connectors[i]);
      if (c && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0 && seen++ == monitor) {
        mode_ = c->modes[0];
        for (int m = 0; m < c->count_modes; ++m)
          if (c->modes[m].type & DRM_MODE_TYPE_PREFERRED) mode_ = c->modes[m];
        connector_ = c->connector_id;
        drmModeEncoder* e = c->encoder_id ? drmModeGetEncoder(fd_, c->encoder_id) : nullptr;
        if (e && e->crtc_id) crtc_ = e->crtc_id;
        for (int k = 0; !crtc_ && k < res->count_crtcs; ++k)
          if (!e || (e->possible_crtcs & (1u << k))) crtc_ = res->crtcs[k];
        if (e) drmModeFreeEncoder(e);
      }
      if (c) drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    if (!crtc_)
      throw Error("gbm: " + card + " has no connected display number " + std::to_string(monitor) +
                  " with a usable mode and CRTC");
    width_ = mode_.hdisplay;
    height_ = mode_.vdisplay;
  }

  EGLConfig choose_config() {
    const EGLint attribs[] = {EGL_SURFACE_TYPE,
                              EGL_WINDOW_BIT,
                              EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_BIT,
                              EGL_RED_SIZE,
                              8,
                              EGL_GREEN_SIZE,
                              8,
                              EGL_BLUE_SIZE,
                              8,
                              EGL_NONE};
    EGLConfig configs[64];
    EGLint count = 0;
    if (!eglChooseConfig(display_, attribs, configs, 64, &count) || count == 0)
      throw Error(egl_error("eglChooseConfig for a GBM window"));
    for (EGLint i = 0; i < count; ++i) {
      EGLint id = 0;
      if (eglGetConfigAttrib(display_, configs[i], EGL_NATIVE_VISUAL_ID, &id) && id == GBM_FORMAT_XRGB8888)
        return configs[i];
    }
    throw Error("gbm: no EGL config matches the XRGB8888 scanout format");
  }

  void release() {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface_);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
      display_ = EGL_NO_DISPLAY;
    }
    if (previous_bo_) {
      drmModeRmFB(fd_, previous_fb_);
      gbm_surface_release_buffer(surface_, previous_bo_);
      previous_bo_ = nullptr;
    }
    if (surface_) gbm_surface_destroy(surface_);
    if (gbm_) gbm_device_destroy(gbm_);
    surface_ = nullptr;
    gbm_ = nullptr;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  int fd_ = -1;
  int width_ = 0, height_ = 0;
  std::uint32_t connector_ = 0, crtc_ = 0, previous_fb_ = 0;
  drmModeModeInfo mode_{};
  gbm_device* gbm_ = nullptr;
  gbm_surface* surface_ = nullptr;
  gbm_bo* previous_bo_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
};

}  // namespace

std::unique_ptr<Backend> make_gbm_backend(const BackendOptions& options) {
  return std::make_unique<GBMBackend>(options);
}

}  // namespace walk::render::detail
