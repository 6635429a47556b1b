#pragma once
// A GL 3.3 core context plus somewhere to draw: an offscreen buffer (OSMesa, EGL) or a window (GLFW).
// create() throws walk::Error with a clear message when the backend is not compiled in or cannot start.
#include <memory>
#include <string>

namespace walk::render {

// GBM: EGL on GBM/KMS, straight to a display with no compositor; never chosen by Auto, only by config.
enum class BackendKind { Auto, OSMesa, EGL, GLFW, GBM };

// "auto", "osmesa", "egl", "glfw", "gbm"; throws walk::Error naming the accepted values otherwise.
[[nodiscard]] BackendKind parse_backend_kind(const std::string& text);
[[nodiscard]] const char* backend_kind_name(BackendKind kind);

struct BackendOptions {
  BackendKind kind = BackendKind::Auto;  // Auto: GLFW when a display is set, else EGL, else OSMesa
  int width = 1280;
  int height = 720;
  bool fullscreen = false;
  int monitor = 0;         // GLFW full screen and GBM: which connected display
  std::string drm_device;  // GBM: e.g. /dev/dri/card1; empty: the first card
  std::string title = "Walkthrough";
  // Quad-buffered stereo (left and right back buffers): asked of GLFW; a context that cannot do it comes up
  // mono and says so through stereo().
  bool stereo = false;
};

class Backend {
 public:
  virtual ~Backend() = default;
  [[nodiscard]] virtual const char* name() const = 0;
  [[nodiscard]] virtual int width() const = 0;
  [[nodiscard]] virtual int height() const = 0;
  virtual void make_current() = 0;
  virtual void present() {}  // swap buffers for a window; headless: no-op
  [[nodiscard]] virtual bool close_requested() { return false; }  // window closed by the user
  virtual void poll_events() {}
  // True when frames must be blitted to the default framebuffer to be seen (Renderer::set_present_to_window).
  [[nodiscard]] virtual bool has_window() const { return false; }
  // Whether the window has left and right back buffers (BackendOptions::stereo granted).
  [[nodiscard]] virtual bool stereo() const { return false; }

  static std::unique_ptr<Backend> create(const BackendOptions& options);
};

}  // namespace walk::render
