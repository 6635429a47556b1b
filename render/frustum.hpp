#pragma once
// View-frustum culling on top of the PVS: boxes against the six planes of the view-projection matrix
// (Gribb & Hartmann). Conservative: a box is dropped only when it lies wholly outside one plane. Pure CPU.
#include <array>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace walk::render {

struct Box {
  std::array<float, 3> lo, hi;  // lo > hi on any axis: empty, never drawn
  [[nodiscard]] bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

// The empty box that any point grown into it becomes.
[[nodiscard]] Box empty_box();
void grow(Box& box, const float point[3]);
// The distance from `eye` to the box's nearest point (0 inside).
[[nodiscard]] float distance_to(const glm::vec3& eye, const Box& box);

class Frustum {
 public:
  explicit Frustum(const glm::mat4& view_projection);
  // False only when the box lies wholly behind one plane (or is empty).
  [[nodiscard]] bool touches(const Box& box) const;

 private:
  std::array<glm::vec4, 6> planes_;
};

}  // namespace walk::render
