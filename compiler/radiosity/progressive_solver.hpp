#pragma once
// Progressive refinement radiosity (Cohen, Chen, Wallace & Greenberg 1988) by ray casting, with one
// radiosity vector per light circuit: every shot carries the unshot power of all circuits along the same
// rays, so any dimmer mix is a linear combination at display time.
//
// Each round shoots every patch whose unshot power is within `batch_fraction` of the largest (the paper's
// "patch with the most unshot power", relaxed so a round's rays can be cast in parallel; the converged answer
// does not depend on the order of shots). Rays per shot are proportional to the unshot power so that power
// per ray stays constant; directions are jittered (stratified) and cosine-distributed, origins uniform on the
// patch.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "compiler/photometry/emission.hpp"
#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/sparse_light.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

// A diffuse area luminaire: a patch that emits `exitance` (W/m2 per channel) on `circuit`.
struct AreaEmitter {
  std::uint32_t patch = 0;
  std::uint32_t circuit = 0;
  model::Rgb exitance{0.0};
};

// A point or spot luminaire: power leaves `position` with intensity proportional to cos^exponent of the angle
// to `axis`, inside a cone of half-angle `cone` (pi: an isotropic point light), or, when `sampler` is set, as
// a measured intensity distribution.
struct PointEmitter {
  model::Vec3 position{0.0};
  model::Vec3 axis{0.0, 0.0, -1.0};
  double cone = 3.141592653589793;
  double exponent = 0.0;
  model::Rgb power{0.0};
  std::uint32_t circuit = 0;
  std::shared_ptr<const EmissionSampler> sampler;
};

struct RadiosityOptions {
  double rays_per_watt = 2000.0;  // accuracy knob: rays shot per watt of unshot power
  double residual = 0.01;         // stop when unshot power < residual * emitted power
  double batch_fraction = 0.5;    // shoot every patch with at least this fraction of the largest unshot power
  unsigned threads = 2;
  std::uint64_t seed = 1;
  std::uint64_t max_rays = 2'000'000'000;  // safety stop
  std::string caster = "axial";            // ray caster by name (compiler/raycast/ray_caster.hpp)
  // The patches' caster (`patches.triangles()` in `caster`'s kind) built by the caller, who solves more
  // than once or gathers from the same patches afterwards; null: the solve builds its own.
  const RayCaster* built_caster = nullptr;
  // Direct light already gathered at the receivers, as the radiosity it gives each patch (a row per patch,
  // W/m2, reflectance applied): when set, luminaires shoot nothing and only this reflected light and what it
  // reflects in turn is shot (Wallace, Elmquist & Haines 1989), so shooting noise is in the indirect light
  // alone. The result's radiosity includes it; `emitted` then counts the power it injects.
  const SparseLight* gathered_direct = nullptr;
};

struct RadiosityStats {
  std::uint64_t rays = 0;
  std::uint64_t shots = 0;
  std::uint64_t rounds = 0;
  // Energy bookkeeping (watts, summed over circuits and channels / 3): emitted = absorbed + escaped +
  // back_face + unshot, up to floating-point rounding.
  double emitted = 0.0;
  double absorbed = 0.0;
  double escaped = 0.0;    // rays that left the model (open windows, holes to the outside)
  double back_face = 0.0;  // rays that hit the back of a one-sided surface (inside a wall): absorbed there
  double unshot = 0.0;
  double seconds = 0.0;
  // The solver's own estimate of its error: every ray carries the same power, so the light a patch
  // reflects is its ray hits h times that power, off by about 1/sqrt(h) (Poisson). Area-weighted RMS of
  // those errors over the area-weighted RMS reflected radiosity: sqrt(sum A B_s^2 / h / sum A B_r^2), B_r
  // the reflected part of B (emission is exact), B_s its shot part (B_r less any gathered direct light),
  // scalar over circuits and channels.
  double estimated_error = 0.0;
};

struct RadiosityResult {
  std::size_t circuits = 0;
  // W/m2, a row per patch: the circuits whose light reaches it (a patch in one room of a building holds
  // a few of its circuits, so this grows with the building, not with patches x circuits).
  SparseLight radiosity;
  RadiosityStats stats;
};

// Called after every round with the result so far (for convergence studies); may be empty.
using RoundObserver = std::function<void(const RadiosityResult&)>;

[[nodiscard]] RadiosityResult solve_radiosity(const PatchSet& patches, std::span<const AreaEmitter> area,
                                              std::span<const PointEmitter> points, std::size_t circuits,
                                              const RadiosityOptions& options,
                                              const RoundObserver& observer = {});

}  // namespace walk::compiler
