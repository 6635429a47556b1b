#include "compiler/lighting/final_gather.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>

#include "common/parallel_for.hpp"
#include "compiler/radiosity/sampling.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {
namespace {

// Ray origins stand this far off the receiver (metres): above the float rounding of bundle vertices, so a
// ray does not meet the receiver's own surface, and far below any room's size.
constexpr double kGatherOffset = 1e-4;
// Noise in a dark corner is judged against this fraction of the room's typical (RMS direct) light, not
// against the corner's own: the eye adapts to the room, and a receiver lit a hundredth as much would
// otherwise take the most rays.
constexpr double kDarkFloor = 0.25;
static_assert(kGatherBatchRays == 16, "a batch is a 4 x 4 grid of strata");

}  // namespace

void inset_from_edges(std::span<SurfaceSample> samples, std::span<const std::uint32_t> sample_vertex,
                      std::span<const model::Vec3> vertices, std::span<const std::uint32_t> indices) {
  std::vector<model::Vec3> inward(vertices.size(), model::Vec3(0.0));
  std::vector<double> room(vertices.size(), kGatherInset);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const model::Vec3 centroid =
        (vertices[indices[t]] + vertices[indices[t + 1]] + vertices[indices[t + 2]]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = indices[t + k];
      const model::Vec3 d = centroid - vertices[v];
      const double length = glm::length(d);
      if (length <= 0.0) continue;
      inward[v] += d / length;
      room[v] = std::min(room[v], 0.5 * length);
    }
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const std::uint32_t v = sample_vertex[i];
    model::Vec3 d = inward[v] - samples[i].normal * glm::dot(inward[v], samples[i].normal);
    const double length = glm::length(d);
    // Directions that cancel (a vertex with triangles all round it) leave a sum far below one unit.
    if (length < 0.5) continue;
    samples[i].position += d * (room[v] / length);
  }
}

SparseLight gather_indirect(const PatchSet& patches, const SparseLight& outgoing,
                            std::span<const SurfaceSample> samples, std::span<const double> shown_direct,
                            const FinalGatherOptions& options, FinalGatherStats* stats) {
  const auto caster = make_ray_caster(options.caster, patches.triangles());
  return gather_indirect(*caster, outgoing, samples, shown_direct, options, stats);
}

SparseLight gather_indirect(const RayCaster& caster, const SparseLight& outgoing,
                            std::span<const SurfaceSample> samples, std::span<const double> shown_direct,
                            const FinalGatherOptions& options, FinalGatherStats* stats) {
  std::uint32_t circuits = 0;
  for (std::size_t r = 0; r < outgoing.rows(); ++r)
    for (const CircuitLight& e : outgoing.row(r)) circuits = std::max(circuits, e.circuit + 1);

  // The error allowed at a receiver is relative to its light, but never to less than kDarkFloor of the
  // RMS direct light over all receivers.
  double direct_square = 0.0;
  for (const double d : shown_direct) direct_square += d * d;
  const double floor =
      shown_direct.empty() ? 0.0 : kDarkFloor * std::sqrt(direct_square / double(shown_direct.size()));

  SparseLight out(samples.size());
  std::vector<double> standard_error(samples.size(), 0.0), shown(samples.size(), 0.0),
      gathered(samples.size(), 0.0);
  std::vector<std::uint8_t> hidden(samples.size(), 0);
  std::atomic<std::uint64_t> rays{0}, capped{0};
  parallel_ranges(samples.size(), 64, options.threads, [&](std::size_t first, std::size_t last) {
    std::vector<double> sum(std::size_t(circuits) * 3, 0.0);  // per circuit and channel, over all rays
    std::vector<std::uint8_t> touched(circuits, 0);
    std::uint64_t my_rays = 0;
    for (std::size_t i = first; i < last; ++i) {
      const SurfaceSample& s = samples[i];
      SplitMix rng(mix_seed(options.seed, i));
      const model::Vec3 origin = s.position + s.normal * kGatherOffset;
      const double albedo = (s.albedo.r + s.albedo.g + s.albedo.b) / 3.0;
      // Each batch puts one ray in each of its 16 strata; the standard error of the stratified mean comes
      // from the spread within each stratum across batches (16 (n - 1) degrees of freedom: the spread of
      // whole batches' means, n - 1, reads zero where every batch happens to hit alike).
      std::array<double, kGatherBatchRays> stratum_sum{}, stratum_sum2{};
      double total = 0.0;
      int n = 0, backs = 0;
      bool met = false;
      // Irradiance is the mean radiosity seen (cosine-weighted rays): its error before the reflectance.
      auto standard_error_of_mean = [&] {
        if (n < 2) return 0.0;
        double variance = 0.0;
        for (int k = 0; k < kGatherBatchRays; ++k)
          variance += std::max(0.0, stratum_sum2[k] - stratum_sum[k] * stratum_sum[k] / n) / (n - 1);
        return std::sqrt(variance / n) / kGatherBatchRays;
      };
      while (n < kGatherMaxBatches) {
        for (int k = 0; k < kGatherBatchRays; ++k) {
          const double u1 = ((k & 3) + rng.uniform()) * 0.25, u2 = ((k >> 2) + rng.uniform()) * 0.25;
          Ray ray{origin, cosine_direction(s.normal, u1, u2)};
          ray.tmin = self_hit_tmin(ray.dir);
          const RayHit hit = caster.closest(ray);
          backs += hit.hit() && !hit.front;
          if (!hit.hit() || !hit.front) continue;  // out of the model, or the inside of a wall
          double seen = 0.0;                       // scalar: mean over channels, sum over circuits
          for (const CircuitLight& e : outgoing.row(hit.polygon)) {
            touched[e.circuit] = 1;
            for (int c = 0; c < 3; ++c) sum[std::size_t(e.circuit) * 3 + c] += e.rgb[c];
            seen += (e.rgb[0] + e.rgb[1] + e.rgb[2]) / 3.0;
          }
          stratum_sum[k] += seen;
          stratum_sum2[k] += seen * seen;
          total += seen;
        }
        my_rays += kGatherBatchRays;
        ++n;
        if (n >= kGatherMinBatches &&
            albedo * standard_error_of_mean() <=
                options.target_error *
                    std::max(floor, shown_direct[i] + albedo * total / (n * kGatherBatchRays))) {
          met = true;
          break;
        }
      }
      capped += !met;
      hidden[i] = 2 * backs > n * kGatherBatchRays;
      standard_error[i] = albedo * standard_error_of_mean();
      gathered[i] = albedo * total / (n * kGatherBatchRays);
      shown[i] = shown_direct[i] + gathered[i];
      const double scale = 1.0 / (n * kGatherBatchRays);
      for (std::uint32_t c = 0; c < circuits; ++c) {
        if (!touched[c]) continue;
        double* b = out.at(i, c);
        for (int k = 0; k < 3; ++k) b[k] = sum[std::size_t(c) * 3 + k] * scale * s.albedo[k];
        for (int k = 0; k < 3; ++k) sum[std::size_t(c) * 3 + k] = 0.0;
        touched[c] = 0;
      }
    }
    rays += my_rays;
  });
  if (stats) {
    double se2 = 0.0, shown2 = 0.0, gathered2 = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      se2 += standard_error[i] * standard_error[i];
      shown2 += shown[i] * shown[i];
      gathered2 += gathered[i] * gathered[i];
    }
    stats->gathered_share = shown2 > 0.0 ? std::sqrt(gathered2 / shown2) : 0.0;
    stats->rays = rays.load();
    stats->capped = capped.load();
    stats->estimated_error = shown2 > 0.0 ? std::sqrt(se2 / shown2) : 0.0;
    stats->hidden = std::move(hidden);
  }
  return out;
}

}  // namespace walk::compiler
