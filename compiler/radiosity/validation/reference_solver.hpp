#pragma once
// An independent reference for the progressive shooter, sharing none of its sampling or solving code:
// form factors from the analytic point-to-polygon contour integral (Lambert; Baum, Rushmeier & Winget 1989)
// averaged over fixed quadrature points, with visibility from fixed rays between quadrature points, and the
// radiosity system B = E + rho F B solved by Gauss-Seidel gathering to round-off. Cost grows with patches^2:
// meant for validation scenes (the Cornell box), not buildings.
#include <span>
#include <vector>

#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/progressive_solver.hpp"

namespace walk::compiler {

struct ReferenceStats {
  double seconds = 0.0;
  std::size_t iterations = 0;
  std::uint64_t visibility_rays = 0;
};

// Single circuit: [patch][channel] radiosity, W/m2.
[[nodiscard]] std::vector<double> reference_radiosity(const PatchSet& patches,
                                                      std::span<const AreaEmitter> emitters, unsigned threads,
                                                      ReferenceStats* stats = nullptr);

// Form factor from a differential area at `x` with unit normal `n` to a polygon, exact (no visibility).
[[nodiscard]] double point_polygon_form_factor(const model::Vec3& x, const model::Vec3& n,
                                               std::span<const model::Vec3> polygon);

}  // namespace walk::compiler
