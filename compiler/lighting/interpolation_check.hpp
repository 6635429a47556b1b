#pragma once
// How far the display's linear interpolation of light between vertices is from the light at the triangles
// themselves. The final gather's estimate is the noise of what each vertex shows; a vertex can be exact and
// the light between vertices still wrong (a falloff or a shadow edge the mesh does not follow), and that,
// not the noise, is most of what the path-traced reference measures. So the light stage also gathers the
// light at random points of a sample of lit triangles, direct and indirect alike, and compares it with what
// the display interpolates there from their corners: the stage's estimate then holds both. The points
// spread over each triangle as a view sees it; a triangle's centroid, where a bump between corners is
// largest, overstated the error.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/lighting/direct_light.hpp"
#include "compiler/radiosity/sparse_light.hpp"

namespace walk::compiler {

// Triangles checked per compile (no more than there are lit vertices): a relative RMS from a sample this
// size has a standard error of a few percent of itself, and gathering at it costs a small share of the
// vertices' gather.
inline constexpr std::size_t kInterpolationChecks = 2000;

struct InterpolationChecks {
  std::vector<SurfaceSample> points;                  // each a point in a triangle, its polygon's normal
  std::vector<std::array<std::uint32_t, 3>> corners;  // the triangle's vertices
  std::vector<std::array<double, 3>> weights;         // the point's barycentric weights of its corners
};

// Up to `count` points, uniform over the area of the triangles (`indices` over `vertices`) whose corners
// are all lit samples (`samples`, at vertices `sample_vertex`), so the check weighs the light as a view of
// the surfaces does. Deterministic for a seed.
[[nodiscard]] InterpolationChecks pick_interpolation_checks(std::span<const SurfaceSample> samples,
                                                            std::span<const std::uint32_t> sample_vertex,
                                                            std::span<const model::Vec3> vertices,
                                                            std::span<const std::uint32_t> indices,
                                                            std::size_t count, std::uint64_t seed);

// The RMS of (the corners' rows of `shown` interpolated at each point - `truth`) over the RMS of `truth`
// (scalars, every circuit at full), with noise taken out in quadrature: `truth_noise` is the relative RMS
// noise of one truth value, `shown_noise` that of one shown vertex, which the interpolation carries by the
// sum of its squared weights (0 where the shown light's noise is error a view sees). Points marked in
// `hidden` (if not empty) are left out: no view sees them, and interpolating across them from lit corners
// is what a display does. 0 without checks or light.
[[nodiscard]] double interpolation_error(const InterpolationChecks& checks, const SparseLight& shown,
                                         std::span<const double> truth, double truth_noise,
                                         double shown_noise, std::span<const std::uint8_t> hidden = {});

}  // namespace walk::compiler
