// Backend selection: names, and Auto's order (a window when a display is set, else EGL, else OSMesa).
#include "render/backend/backend.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "model/error.hpp"
#include "render/backend/backend_factories.hpp"

namespace walk::render {
namespace {

constexpr const char* kAccepted = "auto, osmesa, egl, glfw, gbm";

#if WALK_WITH_OSMESA
constexpr bool kHaveOSMesa = true;
#else
constexpr bool kHaveOSMesa = false;
#endif
#if WALK_WITH_EGL
constexpr bool kHaveEGL = true;
#else
constexpr bool kHaveEGL = false;
#endif
#if WALK_WITH_GLFW
constexpr bool kHaveGLFW = true;
#else
constexpr bool kHaveGLFW = false;
#endif

bool compiled_in(BackendKind kind) {
  switch (kind) {
    case BackendKind::OSMesa:
      return kHaveOSMesa;
    case BackendKind::EGL:
      return kHaveEGL;
    case BackendKind::GLFW:
      return kHaveGLFW;
    case BackendKind::GBM:
#if WALK_WITH_GBM
      return true;
#else
      return false;
#endif
    case BackendKind::Auto:
      return true;
  }
  return false;
}

std::unique_ptr<Backend> create_one(BackendKind kind, const BackendOptions& options) {
  switch (kind) {
#if WALK_WITH_OSMESA
    case BackendKind::OSMesa:
      return detail::make_osmesa_backend(options);
#endif
#if WALK_WITH_EGL
    case BackendKind::EGL:
      return detail::make_egl_backend(options);
#endif
#if WALK_WITH_GLFW
    case BackendKind::GLFW:
      return detail::make_glfw_backend(options);
#endif
#if WALK_WITH_GBM
    case BackendKind::GBM:
      return detail::make_gbm_backend(options);
#endif
    default:
      break;
  }
  throw Error(std::string("render backend '") + backend_kind_name(kind) +
              "' is not compiled into this build; reconfigure with -DWALK_WITH_" +
              (kind == BackendKind::OSMesa ? "OSMESA"
               : kind == BackendKind::EGL  ? "EGL"
               : kind == BackendKind::GBM  ? "GBM"
                                           : "GLFW") +
              "=ON or choose another backend (" + kAccepted + ")");
}

bool display_set() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

}  // namespace

BackendKind parse_backend_kind(const std::string& text) {
  if (text == "auto") return BackendKind::Auto;
  if (text == "osmesa") return BackendKind::OSMesa;
  if (text == "egl") return BackendKind::EGL;
  if (text == "gbm") return BackendKind::GBM;
  if (text == "glfw") return BackendKind::GLFW;
  throw Error("unknown render backend '" + text + "'; accepted values: " + kAccepted);
}

const char* backend_kind_name(BackendKind kind) {
  switch (kind) {
    case BackendKind::Auto:
      return "auto";
    case BackendKind::OSMesa:
      return "osmesa";
    case BackendKind::EGL:
      return "egl";
    case BackendKind::GBM:
      return "gbm";
    case BackendKind::GLFW:
      return "glfw";
  }
  return "unknown";
}

std::unique_ptr<Backend> Backend::create(const BackendOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    throw Error("render backend size " + std::to_string(options.width) + "x" +
                std::to_string(options.height) + " is not positive");
  if (options.kind != BackendKind::Auto) {
    if (!compiled_in(options.kind)) return create_one(options.kind, options);  // throws the reconfigure hint
    try {
      return create_one(options.kind, options);
    } catch (const std::exception& e) {
      throw Error(std::string("render backend '") + backend_kind_name(options.kind) +
                  "' could not start: " + e.what() + "; try another backend (" + kAccepted + ")");
    }
  }
  // Auto: try each candidate in order, logging why one was passed over.
  std::vector<BackendKind> order;
  if (display_set() && compiled_in(BackendKind::GLFW)) order.push_back(BackendKind::GLFW);
  if (compiled_in(BackendKind::EGL)) order.push_back(BackendKind::EGL);
  if (compiled_in(BackendKind::OSMesa)) order.push_back(BackendKind::OSMesa);
  if (order.empty())
    throw Error(
        "no render backend is compiled into this build (GLFW needs DISPLAY or WAYLAND_DISPLAY); "
        "reconfigure with -DWALK_WITH_EGL=ON or -DWALK_WITH_OSMESA=ON");
  std::string reasons;
  for (BackendKind kind : order) {
    try {
      auto backend = create_one(kind, options);
      if (!reasons.empty()) spdlog::info("render backend: using {} ({})", backend->name(), reasons);
      return backend;
    } catch (const std::exception& e) {
      spdlog::warn("render backend {} failed, trying the next one: {}", backend_kind_name(kind), e.what());
      reasons += std::string(reasons.empty() ? "" : "; ") + backend_kind_name(kind) + " failed: " + e.what();
    }
  }
  throw Error("no render backend could start: " + reasons);
}

}  // namespace walk::render
