#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "model/error.hpp"

namespace walk::render {

namespace {

// Screen corners closer than this are one point (metres; screens are centimetres to metres wide).
constexpr double kMinScreenSide = 1e-4;
// Edges whose cosine exceeds this are not at right angles: about 0.6 degrees, far beyond the error of
// corners measured with a tape, well short of a parallelogram anyone would call a rectangle.
constexpr double kRightAngleCosine = 0.01;
// The eye must be at least this far in front of the screen plane (metres): at zero the frustum is infinite.
constexpr double kMinEyeToScreen = 1e-3;

glm::dmat4 screen_projection(const View& view, const ScreenRect& s) {
  if (const std::string problem = screen_problem(s); !problem.empty()) throw Error("view: screen " + problem);
  // Kooima's generalized perspective projection: the screen's right, up and normal axes, the eye's distance
  // to its plane, and the frustum's extents on the near plane.
  const glm::dvec3 right = glm::normalize(s.lower_right - s.lower_left);
  const glm::dvec3 up = glm::normalize(s.upper_left - s.lower_left);
  const glm::dvec3 normal = glm::normalize(glm::cross(right, up));
  const glm::dvec3 to_ll = s.lower_left - view.eye, to_lr = s.lower_right - view.eye,
                   to_ul = s.upper_left - view.eye;
  const double distance = -glm::dot(to_ll, normal);
  if (!(distance > kMinEyeToScreen)) throw Error("view: the eye is not in front of the screen");
  const double k = view.near_plane / distance;
  const glm::dmat4 frustum =
      glm::frustum(glm::dot(right, to_ll) * k, glm::dot(right, to_lr) * k, glm::dot(up, to_ll) * k,
                   glm::dot(up, to_ul) * k, view.near_plane, view.far_plane);
  glm::dmat4 axes(1.0);  // world -> screen axes: rows right, up, normal
  for (int i = 0; i < 3; ++i) {
    axes[i][0] = right[i];
    axes[i][1] = up[i];
    axes[i][2] = normal[i];
  }
  return frustum * axes * glm::translate(glm::dmat4(1.0), -view.eye);
}

}  // namespace

std::string screen_problem(const ScreenRect& s) {
  const glm::dvec3 across = s.lower_right - s.lower_left, up = s.upper_left - s.lower_left;
  const double w = glm::length(across), h = glm::length(up);
  if (!std::isfinite(w) || !std::isfinite(h)) return "has corners that are not finite";
  if (w < kMinScreenSide || h < kMinScreenSide) return "has corners that coincide (zero width or height)";
  if (std::abs(glm::dot(across, up)) > kRightAngleCosine * w * h)
    return "corners do not form a rectangle (lower_left->lower_right and lower_left->upper_left are not at "
           "right angles)";
  return {};
}

double vertical_field_of_view(const View& view) {
  if (!view.screen) return glm::radians(view.fov_y_degrees);
  const ScreenRect& s = *view.screen;
  const glm::dvec3 up = glm::normalize(s.upper_left - s.lower_left);
  const glm::dvec3 normal = glm::normalize(glm::cross(s.lower_right - s.lower_left, up));
  const double distance = std::max(-glm::dot(s.lower_left - view.eye, normal), kMinEyeToScreen);
  const double below = glm::dot(up, s.lower_left - view.eye), above = glm::dot(up, s.upper_left - view.eye);
  return std::atan2(above, distance) - std::atan2(below, distance);
}

glm::mat4 view_projection(const View& view, double aspect) {
  return glm::mat4(view_projection_double(view, aspect));
}

glm::dmat4 view_projection_double(const View& view, double aspect) {
  if (view.screen) {
    if (!(view.near_plane > 0.0) || !(view.far_plane > view.near_plane))
      throw Error("view: need 0 < near_plane < far_plane");
    return screen_projection(view, *view.screen);
  }
  const double length = glm::length(view.forward);
  if (!(length > 0.0) || !std::isfinite(length)) throw Error("view: forward direction is zero or not finite");
  if (!(aspect > 0.0)) throw Error("view: aspect ratio must be positive");
  if (!(view.near_plane > 0.0) || !(view.far_plane > view.near_plane))
    throw Error("view: need 0 < near_plane < far_plane");
  if (!(view.fov_y_degrees > 0.0 && view.fov_y_degrees < 180.0))
    throw Error("view: fov_y_degrees must be between 0 and 180");
  const glm::dvec3 forward = view.forward / length;
  glm::dvec3 up = view.up;
  // Looking straight up or down: any up vector not parallel to forward will do.
  if (glm::length(glm::cross(forward, up)) < 1e-9)
    up = std::abs(forward.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dmat4 v = glm::lookAt(view.eye, view.eye + forward, up);
  const glm::dmat4 p =
      glm::perspective(glm::radians(view.fov_y_degrees), aspect, view.near_plane, view.far_plane);
  return p * v;
}

}  // namespace walk::render
