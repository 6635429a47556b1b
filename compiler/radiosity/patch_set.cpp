#include "compiler/radiosity/patch_set.hpp"

#include <glm/geometric.hpp>

namespace walk::compiler {

// Patches below this area (m^2) carry no meaningful energy and would only add noise: 1 mm^2.
constexpr double kMinPatchArea = 1e-6;

bool PatchSet::add(std::uint32_t a, std::uint32_t b, std::uint32_t c, const model::Rgb& reflectance,
                   std::uint32_t polygon) {
  const model::Vec3 n = glm::cross(vertices[b] - vertices[a], vertices[c] - vertices[a]);
  const double twice_area = glm::length(n);
  if (!(twice_area > 2.0 * kMinPatchArea)) return false;
  patches.push_back({{a, b, c}, n / twice_area, 0.5 * twice_area, reflectance, polygon});
  return true;
}

}  // namespace walk::compiler
