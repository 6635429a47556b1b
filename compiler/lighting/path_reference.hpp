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

// A point on a drawn triangle of the bundle, where both the display's light and the reference are read.
struct SurfacePoint {
  std::uint32_t corners[3];  // VERT ids of its triangle
  double weights[3];         // barycentric
  model::Vec3 position;      // local metres
  model::Vec3 normal;        // unit, the side the display shows
  model::Rgb albedo;
};

// `count` points spread by area over the bundle's opaque and glass triangles, from a fixed seed.
[[nodiscard]] std::vector<SurfacePoint> surface_points(const model::Bundle& bundle, std::size_t count);

// What the display shows there: the vertex light of every circuit at full, interpolated (W/m2 per channel).
[[nodiscard]] model::Rgb displayed_radiosity(const model::Bundle& bundle, const SurfacePoint& p);

struct PathReference {
  std::vector<model::Rgb> radiosity;   // per point: albedo x irradiance, W/m2 per channel
  std::vector<double> standard_error;  // per point, of its luminance-weighted radiosity
  std::uint64_t rays = 0;              // bounce and shadow rays cast
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
