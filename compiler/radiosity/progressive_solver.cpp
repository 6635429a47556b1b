#include "compiler/radiosity/progressive_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "compiler/radiosity/sampling.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {
namespace {

// Rays start this far off their patch along its normal (metres): far above double round-off at building
// scale, far below any real gap, so a ray never re-hits its own patch or a coincident back-to-back wall.
constexpr double kRayOffset = 1e-6;
// Hits within this distance of each other (metres) count as a tie resolved in favour of the face looking back
// at the ray: back-to-back walls drawn once per room are exactly coincident.
constexpr double kTieDistance = 1e-6;
// A patch within this fraction below a round's threshold shoots with it. Every ray carries the same power,
// so patches hit by k and 2k rays tie exactly at batch_fraction 0.5, and float rounding would split such
// ties one way or the other: a scene differing only in rounding (a texture's mean reflectance for the
// material's own) would shoot different patches and differ by the solve's noise, not by the rounding.
// Well above double rounding (1e-16) and a float albedo's (1e-7), well below any real difference.
constexpr double kBatchTie = 1e-6;
constexpr std::int32_t kEscaped = -1;
constexpr std::int32_t kBackFace = -2;
constexpr std::uint32_t kChunkRays = 4096;

struct Shot {
  std::uint32_t patch = 0;  // source patch, or point emitter index when `point`
  bool point = false;
  std::uint32_t rays = 0;
  std::uint64_t first_ray = 0;  // index of its first ray in the round
  // Power per ray of the circuits with power: a patch holds the light of the few circuits that reach its
  // room, so a hit touches those alone.
  std::vector<CircuitLight> power_per_ray;
};

double scalar_power(std::span<const CircuitLight> light) {
  double s = 0.0;
  for (const CircuitLight& e : light)
    for (const double v : e.rgb) s += v;
  return s / 3.0;
}

// Direction for ray `index` of `count` from a point light with intensity ~ cos^n inside a cone: cos(theta)
// is drawn from that distribution itself (inverse CDF), so every ray carries the same power and the shot
// conserves energy exactly. Stratified over (cos theta, phi) for the first side^2 rays.
model::Vec3 point_direction(const PointEmitter& e, std::uint32_t index, std::uint32_t count, SplitMix& rng) {
  const auto side = static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(double(count)))));
  double u1 = rng.uniform(), u2 = rng.uniform();
  if (index < side * side) {
    u1 = ((index % side) + u1) / side;
    u2 = ((index / side) + u2) / side;
  }
  if (e.sampler) return e.sampler->sample(u1, u2);
  const double cos_min = std::cos(std::min(e.cone, std::numbers::pi));
  double cos_theta;
  if (e.exponent > 0.0) {  // pdf ~ cos^n on [max(cos_min, 0), 1]: nothing leaves behind the spot's plane
    const double n1 = e.exponent + 1.0;
    const double lo = std::pow(std::max(cos_min, 0.0), n1);
    cos_theta = std::pow(lo + u1 * (1.0 - lo), 1.0 / n1);
  } else {
    cos_theta = 1.0 - u1 * (1.0 - cos_min);  // uniform in solid angle over the cone
  }
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double phi = 2.0 * std::numbers::pi * u2;
  const model::Vec3 axis = glm::normalize(e.axis);
  const model::Vec3 t = perpendicular(axis);
  const model::Vec3 b = glm::cross(axis, t);
  return t * (sin_theta * std::cos(phi)) + b * (sin_theta * std::sin(phi)) + axis * cos_theta;
}

}  // namespace

RadiosityResult solve_radiosity(const PatchSet& set, std::span<const AreaEmitter> area,
                                std::span<const PointEmitter> points, std::size_t circuits,
                                const RadiosityOptions& options, const RoundObserver& observer) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t P = set.patches.size();
  RadiosityResult result;
  result.circuits = circuits;
  result.radiosity = SparseLight(P);
  auto& stats = result.stats;
  if (circuits == 0 || P == 0) return result;

  std::unique_ptr<RayCaster> own_caster;
  const RayCaster* caster = options.built_caster;
  if (!caster) {
    own_caster = make_ray_caster(options.caster, set.triangles());
    caster = own_caster.get();
  }

  SparseLight unshot(P);
  std::vector<std::uint64_t> patch_hits(P, 0);
  std::vector<double> emitted_exitance(P, 0.0);  // scalar
  const SparseLight* gathered = options.gathered_direct;
  if (gathered && gathered->rows() != P)
    throw std::invalid_argument("solve_radiosity: gathered direct light is not one row per patch");
  for (const auto& e : area) {
    if (e.circuit >= circuits) throw std::invalid_argument("solve_radiosity: emitter circuit out of range");
    emitted_exitance[e.patch] += (e.exitance.r + e.exitance.g + e.exitance.b) / 3.0;
    const auto& p = set.patches[e.patch];
    double* b = result.radiosity.at(e.patch, e.circuit);
    double* u = gathered ? nullptr : unshot.at(e.patch, e.circuit);
    for (int c = 0; c < 3; ++c) {
      b[c] += e.exitance[c];
      if (gathered) continue;  // its direct light is already on the receivers
      u[c] += e.exitance[c] * p.area;
      stats.emitted += e.exitance[c] * p.area / 3.0;
    }
  }
  if (gathered) {
    for (std::size_t i = 0; i < P; ++i) {
      const double a = set.patches[i].area;
      for (const CircuitLight& g : gathered->row(i)) {
        double* b = result.radiosity.at(i, g.circuit);
        double* u = unshot.at(i, g.circuit);
        for (int c = 0; c < 3; ++c) {
          b[c] += g.rgb[c];
          u[c] += g.rgb[c] * a;
          stats.emitted += g.rgb[c] * a / 3.0;
        }
      }
    }
  } else {
    for (const auto& e : points) stats.emitted += (e.power.r + e.power.g + e.power.b) / 3.0;
  }

  std::vector<Shot> shots;
  std::vector<std::int32_t> hits;
  // Each patch's unshot power as a scalar (scalar_power of its row), kept as light arrives and leaves so a
  // round does not rescan every patch's circuits.
  std::vector<double> patch_scalar(P);
  for (std::size_t i = 0; i < P; ++i) patch_scalar[i] = scalar_power(unshot.row(i));
  const unsigned threads = std::max(1u, options.threads);

  auto cast_round = [&](std::uint64_t round) {
    std::uint64_t total = 0;
    for (auto& s : shots) {
      s.first_ray = total;
      total += s.rays;
    }
    hits.assign(total, kEscaped);
    // Work items are chunks of one shot's rays, seeded per chunk: balanced across threads for one huge shot
    // or many small ones, and the same rays whatever the thread count.
    struct Chunk {
      std::uint32_t shot, begin, end;
    };
    std::vector<Chunk> chunks;
    for (std::uint32_t si = 0; si < shots.size(); ++si)
      for (std::uint32_t b = 0; b < shots[si].rays; b += kChunkRays)
        chunks.push_back({si, b, std::min(shots[si].rays, b + kChunkRays)});
    parallel_for(chunks.size(), threads, [&](std::size_t ci) {
      const Chunk& chunk = chunks[ci];
      const Shot& s = shots[chunk.shot];
      const std::uint64_t source = (s.point ? 1ull << 40 : 0) + s.patch;
      SplitMix rng(mix_seed(mix_seed(options.seed, round), source << 20 | chunk.begin / kChunkRays));
      const auto side = static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(double(s.rays)))));
      for (std::uint32_t r = chunk.begin; r < chunk.end; ++r) {
        model::Vec3 origin, dir;
        if (s.point) {
          const PointEmitter& e = points[s.patch];
          origin = e.position;
          dir = point_direction(e, r, s.rays, rng);
        } else {
          const Patch& p = set.patches[s.patch];
          const model::Vec3 o = triangle_point(set.vertices[p.v[0]], set.vertices[p.v[1]],
                                               set.vertices[p.v[2]], rng.uniform(), rng.uniform());
          origin = o + p.normal * kRayOffset;
          // Jittered strata over the cosine-warped square for the first side^2 rays; the rest are plain
          // random (re-using strata for them would favour one side of the hemisphere).
          double u1 = rng.uniform(), u2 = rng.uniform();
          if (r < side * side) {
            u1 = ((r % side) + u1) / side;
            u2 = ((r / side) + u2) / side;
          }
          dir = cosine_direction(p.normal, u1, u2);
        }
        Ray ray{origin, dir, 0.0};
        const RayHit hit = caster->closest(ray);
        std::int32_t out = kEscaped;
        if (hit.hit()) out = hit.front ? static_cast<std::int32_t>(hit.polygon) : kBackFace;
        hits[s.first_ray + r] = out;
      }
    });
    stats.rays += total;
  };

  auto deposit = [&](const Shot& s) {
    const double ray_power = scalar_power(s.power_per_ray);
    for (std::uint32_t r = 0; r < s.rays; ++r) {
      const std::int32_t h = hits[s.first_ray + r];
      if (h < 0) {
        (h == kEscaped ? stats.escaped : stats.back_face) += ray_power;
        continue;
      }
      const Patch& p = set.patches[static_cast<std::size_t>(h)];
      ++patch_hits[static_cast<std::size_t>(h)];
      double gained = 0.0;
      for (const CircuitLight& e : s.power_per_ray) {
        double* b = result.radiosity.at(std::size_t(h), e.circuit);
        double* u = unshot.at(std::size_t(h), e.circuit);
        for (int c = 0; c < 3; ++c) {
          const double in = e.rgb[c];
          const double reflected = in * p.reflectance[c];
          b[c] += reflected / p.area;
          u[c] += reflected;
          gained += reflected;
          stats.absorbed += (in - reflected) / 3.0;
        }
      }
      patch_scalar[std::size_t(h)] += gained / 3.0;
    }
  };

  // Point and spot luminaires shoot once, first: they are not patches and receive nothing.
  if (!points.empty() && !gathered) {
    shots.clear();
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      const auto& e = points[i];
      const double power = (e.power.r + e.power.g + e.power.b) / 3.0;
      Shot s;
      s.patch = i;
      s.point = true;
      s.rays = static_cast<std::uint32_t>(std::max(1.0, std::round(power * options.rays_per_watt)));
      if (e.circuit >= circuits) throw std::invalid_argument("solve_radiosity: emitter circuit out of range");
      s.power_per_ray.push_back({e.circuit, {e.power.r / s.rays, e.power.g / s.rays, e.power.b / s.rays}});
      shots.push_back(std::move(s));
    }
    cast_round(0);
    for (const auto& s : shots) deposit(s);
    ++stats.rounds;
  }

  const double stop = options.residual * stats.emitted;
  // Progress is how far the unshot power has come down towards the residual, on a log scale: each round
  // removes a similar share of what is left, so this fraction grows about evenly with time.
  Progress progress("light", 0, "rounds");
  for (std::uint64_t round = 1;; ++round) {
    double total_unshot = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < P; ++i) {
      total_unshot += patch_scalar[i];
      largest = std::max(largest, patch_scalar[i]);
    }
    stats.unshot = total_unshot;
    if (stats.emitted > 0 && total_unshot > 0 && options.residual > 0 && options.residual < 1)
      progress.set_fraction(std::log(total_unshot / stats.emitted) / std::log(options.residual),
                            fmt::format("unshot {:.2f}% (stops at {:.2f}%)",
                                        100.0 * total_unshot / stats.emitted, 100.0 * options.residual));
    if (total_unshot <= stop || largest <= 0.0 || stats.rays >= options.max_rays) break;
    shots.clear();
    const double threshold = largest * options.batch_fraction * (1.0 - kBatchTie);
    for (std::uint32_t i = 0; i < P; ++i) {
      if (patch_scalar[i] < threshold || patch_scalar[i] <= 0.0) continue;
      // Power per ray stays constant: rays proportional to the unshot power, at least one.
      Shot s;
      s.patch = i;
      s.rays = static_cast<std::uint32_t>(
          std::clamp(std::round(patch_scalar[i] * options.rays_per_watt), 1.0, 4.0e9));
      for (const CircuitLight& u : unshot.row(i))
        s.power_per_ray.push_back({u.circuit, {u.rgb[0] / s.rays, u.rgb[1] / s.rays, u.rgb[2] / s.rays}});
      unshot.clear_row(i);
      patch_scalar[i] = 0.0;
      shots.push_back(std::move(s));
    }
    stats.shots += shots.size();
    cast_round(round);
    for (const auto& s : shots) deposit(s);
    ++stats.rounds;
    progress.advance();
    if (observer) observer(result);
  }
  double variance = 0.0, square = 0.0;
  for (std::size_t i = 0; i < P; ++i) {
    const double a = set.patches[i].area;
    // Scalar radiosity (the mean over channels of the sum over circuits, as scalar_power sums power) less
    // the emitters' own exitance: a panel's glow is exact and would swamp the light on the surfaces.
    const double reflected = std::max(0.0, scalar_power(result.radiosity.row(i)) - emitted_exitance[i]);
    const double shot = gathered ? std::max(0.0, reflected - scalar_power(gathered->row(i))) : reflected;
    square += a * reflected * reflected;
    if (patch_hits[i] > 0) variance += a * shot * shot / double(patch_hits[i]);
  }
  stats.estimated_error = square > 0.0 ? std::sqrt(variance / square) : 0.0;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace walk::compiler
