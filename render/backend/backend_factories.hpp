#pragma once
// Private to the backends: one factory per compiled-in backend, and the glad loader hook they share.
#include <memory>

#include "render/backend/backend.hpp"

namespace walk::render::detail {

#if WALK_WITH_OSMESA
std::unique_ptr<Backend> make_osmesa_backend(const BackendOptions& options);
#endif
#if WALK_WITH_EGL
std::unique_ptr<Backend> make_egl_backend(const BackendOptions& options);
#endif
#if WALK_WITH_GBM
std::unique_ptr<Backend> make_gbm_backend(const BackendOptions& options);
#endif
#if WALK_WITH_GLFW
std::unique_ptr<Backend> make_glfw_backend(const BackendOptions& options);
#endif

}  // namespace walk::render::detail
