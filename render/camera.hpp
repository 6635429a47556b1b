#pragma once
// View and projection from a View, computed in double precision and handed to GL as float.
#include <glm/mat4x4.hpp>

#include "render/renderer.hpp"

namespace walk::render {

// Right-handed, z up; throws walk::Error for a zero forward vector, a non-positive aspect or bad planes.
[[nodiscard]] glm::mat4 view_projection(const View& view, double aspect);

}  // namespace walk::render
