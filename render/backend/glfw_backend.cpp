// GLFW: a window (optionally fullscreen on a chosen monitor) with a core 3.3 forward-compatible context.
// The renderer still draws into its own FBO and blits it to the window before present().
#include <glad/gl.h>
// After glad, so GLFW does not include the system GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <spdlog/spdlog.h>

#include <string>

#include "model/error.hpp"
#include "render/backend/backend_factories.hpp"
#include "render/gl_loader.hpp"

namespace walk::render::detail {
namespace {

void log_glfw_error(int code, const char* description) {
  spdlog::warn("glfw error 0x{:x}: {}", code, description);
}

// GLFW is initialised once for all windows (several outputs each have one) and terminated with the last:
// glfwTerminate destroys every window, so no backend may call it while another lives. GL runs on one thread.
int g_glfw_users = 0;
bool acquire_glfw() {
  return g_glfw_users++ > 0 || glfwInit();
}
void release_glfw() {
  if (--g_glfw_users == 0) glfwTerminate();
}

class GLFWBackend final : public Backend {
 public:
  explicit GLFWBackend(const BackendOptions& options) {
    glfwSetErrorCallback(log_glfw_error);
    if (!acquire_glfw()) {
      release_glfw();
      throw Error("glfw: glfwInit failed (is DISPLAY or WAYLAND_DISPLAY set to a running server?)");
    }
    GLFWmonitor* monitor = nullptr;
    int width = options.width, height = options.height;
    if (options.fullscreen) {
      int count = 0;
      GLFWmonitor** monitors = glfwGetMonitors(&count);
      if (count == 0) {
        release_glfw();
        throw Error("glfw: fullscreen asked for, but no monitor is connected");
      }
      if (options.monitor < 0 || options.monitor >= count) {
        release_glfw();
        throw Error("glfw: monitor " + std::to_string(options.monitor) + " asked for, but only " +
                    std::to_string(count) + " are connected (0.." + std::to_string(count - 1) + ")");
      }
      monitor = monitors[options.monitor];
      // The monitor's current mode: no mode switch, so the kiosk comes up fast and at native resolution.
      const GLFWvidmode* mode = glfwGetVideoMode(monitor);
      glfwWindowHint(GLFW_RED_BITS, mode->redBits);
      glfwWindowHint(GLFW_GREEN_BITS, mode->greenBits);
      glfwWindowHint(GLFW_BLUE_BITS, mode->blueBits);
      glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
      width = mode->width;
      height = mode->height;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 0);  // depth lives in the renderer's FBO
    if (options.stereo) {
      glfwWindowHint(GLFW_STEREO, GLFW_TRUE);
      window_ = glfwCreateWindow(width, height, options.title.c_str(), monitor, nullptr);
      glfwWindowHint(GLFW_STEREO, GLFW_FALSE);
      stereo_ = window_ != nullptr;  // no quad-buffered visual: fall back to a mono window below
    }
    if (!window_) window_ = glfwCreateWindow(width, height, options.title.c_str(), monitor, nullptr);
    if (!window_) {
      release_glfw();
      throw Error("glfw: could not create a " + std::to_string(width) + "x" + std::to_string(height) +
                  " window with a GL 3.3 core context");
    }
    try {
      make_current();
    } catch (...) {
      glfwDestroyWindow(window_);
      release_glfw();
      throw;
    }
    glfwSwapInterval(1);
  }
  ~GLFWBackend() override {
    glfwDestroyWindow(window_);
    release_glfw();
  }

  const char* name() const override { return "glfw"; }
  bool stereo() const override { return stereo_; }
  int width() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
  }
  bool has_window() const override { return true; }
  void make_current() override {
    glfwMakeContextCurrent(window_);
    load_gl(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress), "glfw");
  }
  void present() override { glfwSwapBuffers(window_); }
  bool close_requested() override { return glfwWindowShouldClose(window_); }
  void poll_events() override { glfwPollEvents(); }

 private:
  GLFWwindow* window_ = nullptr;
  bool stereo_ = false;
};

}  // namespace

std::unique_ptr<Backend> make_glfw_backend(const BackendOptions& options) {
  return std::make_unique<GLFWBackend>(options);
}

}  // namespace walk::render::detail
