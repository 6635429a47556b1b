#pragma once
// Indirect light gathered at each display vertex from the solved patches ("final gather": Reichert 1992,
// Lischinski, Tampieri & Greenberg 1993). Shooting leaves each patch's light constant over the patch, so the
// light a receiver shows follows the grid: a small room's ceiling, lit only by its walls, reads a quarter low
// at 0.4 m (docs/RADIOSITY.md). Gathering asks, at the receiver itself, what the solved surfaces send it:
// cosine-distributed rays, each reading the radiosity (less emission: direct light is gathered apart) of the
// patch it meets. The answer then depends on where the receiver is, not on which patch holds it; the
// patches' own shooting noise is averaged over every patch a receiver sees.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "compiler/lighting/direct_light.hpp"
#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/sparse_light.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

struct FinalGatherOptions {
  // Relative standard error each receiver's shown light (direct + gathered) is gathered to; a receiver
  // darker than a quarter of the RMS direct light is held to that quarter (final_gather.cpp).
  double target_error = 0.05;
  unsigned threads = 2;
  std::uint64_t seed = 1;
  std::string caster = "axial";  // ray caster by name (compiler/raycast/ray_caster.hpp)
};

struct FinalGatherStats {
  std::uint64_t rays = 0;
  std::uint64_t capped = 0;  // receivers that stopped at the ray cap above their target
  // RMS of the receivers' standard errors over the RMS of their shown light (scalar, every circuit at full).
  double estimated_error = 0.0;
  // RMS of the gathered light over the RMS of the shown light: the share of what is shown that carries the
  // patches' shooting noise (at most the solver's relative error, less where a receiver sees many patches).
  double gathered_share = 0.0;
  // Per sample: most of its rays met a surface's back, so no view sees it (inside a solid, or a ceiling
  // just behind a lamp's panel), as the path-traced reference judges its points.
  std::vector<std::uint8_t> hidden;
};

// Rays per batch (a 4 x 4 jittered grid over the hemisphere) and the bounds on batches per receiver: the
// standard error is read from the spread within each stratum across batches, which wants two at least; a
// receiver whose light is a wide mix of bright and dark surfaces stops at the cap.
inline constexpr int kGatherBatchRays = 16;
inline constexpr int kGatherMinBatches = 4;
inline constexpr int kGatherMaxBatches = 64;

// A receiver on a polygon's edge stands in the plane of the wall that meets it there, and half its rays
// would leave through that wall into the next room: each sample moves up to kGatherInset into its own
// polygon (along the mean of the directions to its triangles' centroids; `indices`: the display's triangles
// over `vertices`, sample i at vertex sample_vertex[i]). A sample inside a polygon stays where it is.
inline constexpr double kGatherInset = 0.01;  // metres: half the finest grid (kMinGrid); light varies little
void inset_from_edges(std::span<SurfaceSample> samples, std::span<const std::uint32_t> sample_vertex,
                      std::span<const model::Vec3> vertices, std::span<const std::uint32_t> indices);

// Light reflected at each sample (a row each, W/m2, reflectance applied) from `outgoing`, each patch's
// radiosity less its emission (a row per patch of `patches`). A ray that leaves the model or meets a
// surface's back (the inside of a wall) brings nothing. `shown_direct`: each sample's direct light as
// shown (scalar, every circuit at full), which the target is relative to with the gathered light.
[[nodiscard]] SparseLight gather_indirect(const PatchSet& patches, const SparseLight& outgoing,
                                          std::span<const SurfaceSample> samples,
                                          std::span<const double> shown_direct,
                                          const FinalGatherOptions& options,
                                          FinalGatherStats* stats = nullptr);
// The same with the patches' caster built once by the caller (`patches.triangles()` in `options.caster`'s
// kind), for several gathers over one solve.
[[nodiscard]] SparseLight gather_indirect(const RayCaster& caster, const SparseLight& outgoing,
                                          std::span<const SurfaceSample> samples,
                                          std::span<const double> shown_direct,
                                          const FinalGatherOptions& options,
                                          FinalGatherStats* stats = nullptr);

}  // namespace walk::compiler
