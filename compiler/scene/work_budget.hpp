#pragma once
// Work budgets checked before the work: the knobs that multiply cost ([lighting] rays_per_watt and grid) are
// turned into an estimate of rays and of memory before anything is allocated, and a compile above the
// documented limit stops at once with an error naming the key, the estimate and the limit, instead of
// running for hours or dying of std::bad_alloc.
#include <cstddef>
#include <cstdint>

#include "compiler/scene/scene_config.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Rays of the first round alone (rays_per_watt x the luminaires' power; reflections add more): 2e9 is about
// 1.4 hours at the 0.4 Mrays/s the solver casts on 2 cores, past which a knob is a typo, not a choice.
inline constexpr double kMaxFirstRoundRays = 2e9;

// Memory per lighting patch, all stages together: 2 KiB measured as the compile's peak resident size over
// its patches (Sibenik at grid 2 m: 227 MB for 105,452 patches, one circuit), plus the per-circuit light of
// about 2.4 vertices a patch in float and the solver's per-patch doubles, for each circuit that reaches the
// patch: light is sparse (compiler/radiosity/sparse_light.hpp), and a room is lit by its own circuits and a
// few of its neighbours'. Up to kCircuitsReachingAPatch circuits are counted: the generated M building with
// its 170 circuits holds 2.8 a vertex (its compile 2.95 GB at peak, where counting all 170 estimated 18 GB).
inline constexpr double kBytesPerPatch = 2048.0;
inline constexpr double kBytesPerPatchCircuit = 96.0;
inline constexpr double kCircuitsReachingAPatch = 8.0;
// Share of the machine's physical memory a compile may plan to use.
inline constexpr double kMemoryShare = 0.8;

[[nodiscard]] std::uint64_t physical_memory_bytes();

// Patches the mesh stage will make: each drawn face diced on the grid, at least one patch each.
[[nodiscard]] double estimated_patches(const model::Model& model, double grid);

// Throw walk::Error naming the scene file and key when the estimate passes the limit. `memory_bytes` is the
// machine's (a parameter so tests can ask as a smaller machine).
void check_patch_budget(const model::Model& model, const SceneConfig& config, std::uint64_t memory_bytes);
void check_ray_budget(const model::Model& model, const SceneConfig& config);

}  // namespace walk::compiler
