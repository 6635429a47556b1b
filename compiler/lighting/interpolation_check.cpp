#include "compiler/lighting/interpolation_check.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <random>

namespace walk::compiler {

InterpolationChecks pick_interpolation_checks(std::span<const SurfaceSample> samples,
                                              std::span<const std::uint32_t> sample_vertex,
                                              std::span<const model::Vec3> vertices,
                                              std::span<const std::uint32_t> indices, std::size_t count,
                                              std::uint64_t seed) {
  constexpr std::uint32_t kUnlit = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> sample_of(vertices.size(), kUnlit);
  for (std::size_t i = 0; i < sample_vertex.size(); ++i)
    if (sample_vertex[i] < sample_of.size()) sample_of[sample_vertex[i]] = static_cast<std::uint32_t>(i);
  // Lit triangles and their running area.
  std::vector<std::size_t> lit;
  std::vector<double> running;
  double total = 0.0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (std::max({a, b, c}) >= vertices.size()) continue;
    if (sample_of[a] == kUnlit || sample_of[b] == kUnlit || sample_of[c] == kUnlit) continue;
    const double area = 0.5 * glm::length(glm::cross(vertices[b] - vertices[a], vertices[c] - vertices[a]));
    if (!(area > 0.0)) continue;
    total += area;
    lit.push_back(t);
    running.push_back(total);
  }
  InterpolationChecks out;
  if (lit.empty() || count == 0) return out;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (std::size_t k = 0; k < count; ++k) {
    const auto it = std::lower_bound(running.begin(), running.end(), u01(rng) * total);
    const std::size_t t = lit[std::min<std::size_t>(it - running.begin(), lit.size() - 1)];
    const std::array<std::uint32_t, 3> corners{indices[t], indices[t + 1], indices[t + 2]};
    const double r = std::sqrt(u01(rng)), q = u01(rng);  // uniform over the triangle
    const std::array<double, 3> w{1.0 - r, r * (1.0 - q), r * q};
    SurfaceSample p = samples[sample_of[corners[0]]];  // one polygon: one normal and reflectance
    p.position = vertices[corners[0]] * w[0] + vertices[corners[1]] * w[1] + vertices[corners[2]] * w[2];
    out.points.push_back(p);
    out.corners.push_back(corners);
    out.weights.push_back(w);
  }
  return out;
}

double interpolation_error(const InterpolationChecks& checks, const SparseLight& shown,
                           std::span<const double> truth, double truth_noise, double shown_noise,
                           std::span<const std::uint8_t> hidden) {
  double difference = 0.0, light = 0.0, squared_weights = 0.0;
  std::size_t used = 0;
  const std::size_t n = std::min(checks.corners.size(), truth.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (k < hidden.size() && hidden[k]) continue;
    double interpolated = 0.0;
    for (int i = 0; i < 3; ++i) {
      interpolated += shown.scalar(checks.corners[k][i]) * checks.weights[k][i];
      squared_weights += checks.weights[k][i] * checks.weights[k][i];
    }
    difference += (interpolated - truth[k]) * (interpolated - truth[k]);
    light += truth[k] * truth[k];
    ++used;
  }
  if (!(light > 0.0)) return 0.0;
  const double interpolated_noise = squared_weights / double(used);
  return std::sqrt(std::max(
      0.0, difference / light - truth_noise * truth_noise - interpolated_noise * shown_noise * shown_noise));
}

}  // namespace walk::compiler
