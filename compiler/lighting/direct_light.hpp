#pragma once
// The skeleton's lighting: direct light from area luminaires with ray-cast shadows, one radiosity vector per
// circuit at each surface sample. It is a real estimate (no bounce light yet; the display adds an ambient
// term), replaced by progressive radiosity in issue 6 behind the same output layout.
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/radiosity/sparse_light.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct SurfaceSample {
  model::Vec3 position;
  model::Vec3 normal;  // unit
  model::Rgb albedo;
};

struct DirectLightOptions {
  int samples_per_luminaire = 8;
  unsigned threads = 2;
};

struct DirectLightStats {
  std::uint64_t shadow_rays = 0;
  std::uint64_t occluded = 0;
};

// Returns radiosity B (W/m2) per sample (a row each) and circuit.
[[nodiscard]] SparseLight direct_light(std::span<const SurfaceSample> samples,
                                       const std::vector<model::Luminaire>& luminaires,
                                       std::size_t circuit_count, const TriangleBvh& occluders,
                                       const DirectLightOptions& options, DirectLightStats* stats = nullptr);

}  // namespace walk::compiler
