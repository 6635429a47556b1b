#include "compiler/radiosity/validation/display_error.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "compiler/radiosity/sampling.hpp"

namespace walk::compiler {
namespace {

// A probe counts as inside a triangle when its barycentric coordinates are above -this: probes sit on shared
// edges often (they are sampled from another dicing), and either neighbour's interpolation is right there.
constexpr double kBarycentricSlack = 1e-7;

bool barycentric(const model::Vec3& p, const model::Vec3& a, const model::Vec3& b, const model::Vec3& c,
                 double& u, double& v) {
  const model::Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double dp1 = glm::dot(d, e1), dp2 = glm::dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return false;
  u = (d22 * dp1 - d12 * dp2) / det;
  v = (d11 * dp2 - d12 * dp1) / det;
  return u >= -kBarycentricSlack && v >= -kBarycentricSlack && u + v <= 1.0 + kBarycentricSlack;
}

}  // namespace

std::vector<ErrorProbe> make_probes(const ShadedMesh& mesh, double per_square_metre) {
  std::vector<ErrorProbe> out;
  SplitMix rng(0x5eedULL);
  for (std::uint32_t poly = 0; poly < mesh.polygon_triangles.size(); ++poly) {
    const auto& tris = mesh.polygon_triangles[poly];
    std::vector<double> cumulative;
    double total = 0.0;
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
      const auto& a = mesh.vertices[tris[i]];
      total += 0.5 * glm::length(glm::cross(mesh.vertices[tris[i + 1]] - a, mesh.vertices[tris[i + 2]] - a));
      cumulative.push_back(total);
    }
    if (total <= 0.0) continue;
    const auto count = static_cast<std::size_t>(std::max(1.0, std::round(total * per_square_metre)));
    for (std::size_t k = 0; k < count; ++k) {
      const double pick = rng.uniform() * total;
      std::size_t t = 0;
      while (t + 1 < cumulative.size() && cumulative[t] < pick) ++t;
      const auto& a = mesh.vertices[tris[3 * t]];
      const auto& b = mesh.vertices[tris[3 * t + 1]];
      const auto& c = mesh.vertices[tris[3 * t + 2]];
      out.push_back({poly, triangle_point(a, b, c, rng.uniform(), rng.uniform())});
    }
  }
  return out;
}

std::vector<double> evaluate(const ShadedMesh& mesh, const std::vector<ErrorProbe>& probes) {
  std::vector<double> out(probes.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const auto& tris = mesh.polygon_triangles[probes[k].polygon];
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
      double u, v;
      if (!barycentric(probes[k].position, mesh.vertices[tris[i]], mesh.vertices[tris[i + 1]],
                       mesh.vertices[tris[i + 2]], u, v))
        continue;
      out[k] =
          (1.0 - u - v) * mesh.value[tris[i]] + u * mesh.value[tris[i + 1]] + v * mesh.value[tris[i + 2]];
      break;
    }
  }
  return out;
}

DisplayError compare(const std::vector<double>& values, const std::vector<double>& reference) {
  DisplayError e;
  double sum = 0.0, sum_ref = 0.0, sq = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (std::isnan(values[k]) || std::isnan(reference[k])) continue;
    sum += values[k];
    sum_ref += reference[k];
    sq += (values[k] - reference[k]) * (values[k] - reference[k]);
    ++e.probes;
  }
  if (e.probes == 0 || sum_ref <= 0.0) return e;
  const double mean_ref = sum_ref / e.probes;
  e.rms = std::sqrt(sq / e.probes) / mean_ref;
  e.mean_ratio = sum / sum_ref;
  return e;
}

}  // namespace walk::compiler
