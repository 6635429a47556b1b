#pragma once
// View and projection from a View, computed in double precision and handed to GL as float.
#include <glm/mat4x4.hpp>
#include <string>

#include "render/renderer.hpp"

namespace walk::render {

// Right-handed, z up; throws walk::Error for a zero forward vector, a non-positive aspect or bad planes.
// With view.screen: the off-axis frustum from the eye through the screen rectangle (aspect unused); throws
// for a screen that is not a rectangle or an eye not in front of it.
[[nodiscard]] glm::mat4 view_projection(const View& view, double aspect);
// The same before it is handed to GL: the tools unproject pixels through its inverse.
[[nodiscard]] glm::dmat4 view_projection_double(const View& view, double aspect);

// Radians the image spans vertically: fov_y_degrees, or what the screen subtends from the eye.
[[nodiscard]] double vertical_field_of_view(const View& view);

// Why a screen is not usable, or empty: corners that do not form a rectangle of positive size.
[[nodiscard]] std::string screen_problem(const ScreenRect& screen);

}  // namespace walk::render
