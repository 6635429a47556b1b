#pragma once
// A 2D coordinate frame in a polygon's plane: (u, v, normal) is right-handed, so a loop that is
// counter-clockwise about the normal in 3D is counter-clockwise in (u, v).
#include <glm/vec2.hpp>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct PlaneFrame {
  model::Vec3 origin{0.0};
  model::Vec3 u{1.0, 0.0, 0.0};
  model::Vec3 v{0.0, 1.0, 0.0};
  model::Vec3 normal{0.0, 0.0, 1.0};

  [[nodiscard]] glm::dvec2 to_2d(const model::Vec3& p) const;
  [[nodiscard]] model::Vec3 to_3d(const glm::dvec2& q) const { return origin + u * q.x + v * q.y; }
  // Signed distance of `p` from the plane, positive on the normal's side.
  [[nodiscard]] double distance(const model::Vec3& p) const;
  // `p` moved along the normal onto the plane.
  [[nodiscard]] model::Vec3 project(const model::Vec3& p) const { return p - normal * distance(p); }
};

// Frame of a polygon's outer boundary: origin at its first vertex, normal by Newell's method, u along its
// longest edge (so grids and slabs line up with walls). False for a degenerate (zero-area) boundary.
bool plane_frame(const std::vector<model::Vec3>& vertices, PlaneFrame& out);

}  // namespace walk::compiler
