#pragma once
// Light refinement splits the dicing's triangles (the solver's patches) into smaller display triangles
// that keep the patches' corners and add vertices of their own. Light crosses between the two in both
// directions: a vertex the refinement added reads the shot light of the patch it lies on, and a patch
// shoots the mean of the direct light gathered over the display triangles on it. Its three corners alone
// miss what the refinement found inside it (a wall's bright band under a lamp, a shadow edge), and every
// bounce of indirect light would inherit that bias.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/sparse_light.hpp"
#include "compiler/raycast/triangle_bvh.hpp"

namespace walk::compiler {

class PatchLocator {
 public:
  explicit PatchLocator(const PatchSet& patches);

  struct Location {
    std::uint32_t patch = 0;
    std::array<double, 3> weights{};  // of the patch's corners at the point
  };
  // The patch under `point` of a surface facing `normal` (unit), by a short ray onto the patches' fronts;
  // nullopt where the ray slips between two patches' edges.
  [[nodiscard]] std::optional<Location> locate(const model::Vec3& point, const model::Vec3& normal) const;

 private:
  const PatchSet& patches_;
  TriangleBvh bvh_;
};

// A row per patch: the area mean over the display triangles (`display_indices`, over the patches'
// vertices) that lie on it of the light `per_vertex` interpolates across each triangle. A patch on which
// no display triangle was found takes the mean of its corners.
[[nodiscard]] SparseLight patch_area_means(const PatchSet& patches,
                                           std::span<const std::uint32_t> display_indices,
                                           const SparseLight& per_vertex, const PatchLocator& locator,
                                           unsigned threads);

}  // namespace walk::compiler
