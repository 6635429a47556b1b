#pragma once
// How far the display's linear interpolation of light between vertices is from the light at the triangles
// themselves. The final gather's estimate is the noise of what each vertex shows; a vertex can be exact and
// the light between vertices still wrong (a falloff or a shadow edge the mesh does not follow), and that,
// not the noise, is most of what the path-traced reference measures. So the light stage also gathers the
// light at the centroids of a sample of lit triangles, direct and indirect alike, and compares it with the
// mean of their corners: the stage's estimate then holds both.
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
  std::vector<SurfaceSample> points;                  // each a triangle's centroid, its polygon's normal
  std::vector<std::array<std::uint32_t, 3>> corners;  // the triangle's vertices
};

// Up to `count` centroids of the triangles (`indices` over `vertices`) whose corners are all lit samples
// (`samples`, at vertices `sample_vertex`), drawn with probability proportional to area, so the check
// weighs the light as a view of the surfaces does. Deterministic for a seed.
[[nodiscard]] InterpolationChecks pick_interpolation_checks(std::span<const SurfaceSample> samples,
                                                            std::span<const std::uint32_t> sample_vertex,
                                                            std::span<const model::Vec3> vertices,
                                                            std::span<const std::uint32_t> indices,
                                                            std::size_t count, std::uint64_t seed);

// The RMS of (mean of the corners' rows of `shown` - `truth`) over the RMS of `truth` (scalars, every
// circuit at full), with the noise of both taken out in quadrature: `noise` is the relative RMS noise of
// one gathered value, which the truth carries once and the mean of three corners a third of. 0 without
// checks or light.
[[nodiscard]] double interpolation_error(const InterpolationChecks& checks, const SparseLight& shown,
                                         std::span<const double> truth, double noise);

}  // namespace walk::compiler
