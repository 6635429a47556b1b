#include "render/frustum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace walk::render {

Box empty_box() {
  constexpr float kBig = std::numeric_limits<float>::max();
  return Box{{kBig, kBig, kBig}, {-kBig, -kBig, -kBig}};
}

void grow(Box& box, const float point[3]) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], point[k]);
    box.hi[k] = std::max(box.hi[k], point[k]);
  }
}

float distance_to(const glm::vec3& eye, const Box& box) {
  float d2 = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float d = std::max({box.lo[k] - eye[k], 0.0f, eye[k] - box.hi[k]});
    d2 += d * d;
  }
  return std::sqrt(d2);
}

Frustum::Frustum(const glm::mat4& m) {
  // Rows of the matrix (glm is column-major: m[column][row]); plane = row3 +/- row i.
  auto row = [&](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  planes_ = {row(3) + row(0), row(3) - row(0), row(3) + row(1),
             row(3) - row(1), row(3) + row(2), row(3) - row(2)};
}

bool Frustum::touches(const Box& b) const {
  if (b.empty()) return false;
  for (const glm::vec4& p : planes_) {
    // The box corner furthest along the plane's normal: if even it is behind, the whole box is.
    const float x = p.x >= 0.0f ? b.hi[0] : b.lo[0];
    const float y = p.y >= 0.0f ? b.hi[1] : b.lo[1];
    const float z = p.z >= 0.0f ? b.hi[2] : b.lo[2];
    if (p.x * x + p.y * y + p.z * z + p.w < 0.0f) return false;
  }
  return true;
}

}  // namespace walk::render
