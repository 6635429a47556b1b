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
    SurfaceSample p = samples[sample_of[corners[0]]];  // one polygon: one normal and reflectance
    p.position = (vertices[corners[0]] + vertices[corners[1]] + vertices[corners[2]]) / 3.0;
    out.points.push_back(p);
    out.corners.push_back(corners);
  }
  return out;
}

double interpolation_error(const InterpolationChecks& checks, const SparseLight& shown,
                           std::span<const double> truth, double noise) {
  double difference = 0.0, light = 0.0;
  for (std::size_t k = 0; k < checks.corners.size() && k < truth.size(); ++k) {
    double mean = 0.0;
    for (const std::uint32_t v : checks.corners[k]) mean += shown.scalar(v) / 3.0;
    difference += (mean - truth[k]) * (mean - truth[k]);
    light += truth[k] * truth[k];
  }
  if (!(light > 0.0)) return 0.0;
  return std::sqrt(std::max(0.0, difference / light - (1.0 + 1.0 / 3.0) * noise * noise));
}

}  // namespace walk::compiler
