#pragma once
// Barycentric weights of a point in a triangle, the way light stored at corners is read at a point.
#include <array>

#include "model/model.hpp"

namespace walk::compiler {

// Weights of `p`'s projection into the plane of (a, b, c) at corners a, b, c, clamped into the triangle so
// a point just outside (float rounding of the stored vertices) reads its nearest edge. They sum to 1. A
// degenerate triangle (zero area: repeated or collinear corners) gives equal thirds.
[[nodiscard]] std::array<double, 3> triangle_weights(const model::Vec3& a, const model::Vec3& b,
                                                     const model::Vec3& c, const model::Vec3& p);

}  // namespace walk::compiler
