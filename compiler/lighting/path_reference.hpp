#pragma once
// An independent reference for the light a bundle shows: Monte Carlo path tracing of irradiance at surface
// points, sharing no code with the radiosity solver (its own ray queries through TriangleBvh, its own
// luminaire sampling, no patches): next-event estimation from one luminaire drawn by power at each bounce,
// cosine-distributed bounces with Russian roulette. Converges to the exact answer for the bundle's
// geometry, reflectances and luminaires, all circuits at full; its own standard error is measured.
#include <cstdint>
#include <memory>
#include <vector>

#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// A point on a drawn surface of the bundle, where both the display's light (StoredLight::on_surface, so
// bundles diced differently are read at the same points) and the reference are read.
struct SurfacePoint {
  model::Vec3 position;  // local metres
  model::Vec3 normal;    // unit, the side the display shows
  model::Rgb albedo;
};

// `count` points spread by area over the bundle's opaque and glass triangles, from a fixed seed.
[[nodiscard]] std::vector<SurfacePoint> surface_points(const model::Bundle& bundle, std::size_t count);

struct PathReference {
  std::vector<model::Rgb> radiosity;   // per point: albedo x irradiance, W/m2 per channel
  std::vector<double> standard_error;  // per point, of its luminance-weighted radiosity
  // Per point: most of its first bounces meet back faces, so it lies inside a solid or behind a lamp's
  // panel, where no view sees it (a floor under a box): comparisons leave it out.
  std::vector<std::uint8_t> hidden;
  std::uint64_t rays = 0;  // bounce and shadow rays cast
  double seconds = 0.0;
};

class PathTracer {
 public:
  explicit PathTracer(const model::Bundle& bundle);
  ~PathTracer();
  [[nodiscard]] PathReference trace(const std::vector<SurfacePoint>& points, int paths_per_point,
                                    std::uint64_t seed, unsigned threads) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace walk::compiler
