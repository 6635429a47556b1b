#include "compiler/radiosity/patch_set.hpp"

#include <glm/geometric.hpp>

namespace walk::compiler {

// Only degenerate triangles are refused (1e-12 m^2: a 1 um x 1 um sliver, round-off at building scale).
// Small real ones stay: furniture detail in the measured conference room is mostly under 1 mm^2, and a
// triangle left out of the patch set would get no light at its vertices and show black.
constexpr double kMinPatchArea = 1e-12;

bool PatchSet::add(std::uint32_t a, std::uint32_t b, std::uint32_t c, const model::Rgb& reflectance,
                   std::uint32_t polygon) {
  const model::Vec3 n = glm::cross(vertices[b] - vertices[a], vertices[c] - vertices[a]);
  const double twice_area = glm::length(n);
  if (!(twice_area > 2.0 * kMinPatchArea)) return false;
  patches.push_back({{a, b, c}, n / twice_area, 0.5 * twice_area, reflectance, polygon});
  return true;
}

std::vector<Triangle> PatchSet::triangles() const {
  std::vector<Triangle> out;
  out.reserve(patches.size());
  for (std::uint32_t i = 0; i < patches.size(); ++i) {
    const Patch& p = patches[i];
    out.push_back({vertices[p.v[0]], vertices[p.v[1]], vertices[p.v[2]], i});
  }
  return out;
}

}  // namespace walk::compiler
