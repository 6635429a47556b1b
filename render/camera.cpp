#include "render/camera.hpp"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "model/error.hpp"

namespace walk::render {

glm::mat4 view_projection(const View& view, double aspect) {
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
  return glm::mat4(p * v);
}

}  // namespace walk::render
