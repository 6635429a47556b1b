#include "compiler/radiosity/validation/reference_solver.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "common/parallel_for.hpp"
#include "compiler/raycast/triangle_bvh.hpp"

namespace walk::compiler {
namespace {

// Polygon parts closer than this (metres) to the receiver's tangent plane are clipped away: they subtend no
// solid angle above the surface, and keeping them makes the contour integral ill-conditioned.
constexpr double kHorizon = 1e-9;
// Visibility rays stop this fraction short of their target point on the far patch so they never hit it.
constexpr double kShortOfTarget = 1e-6;
constexpr double kRayOffset = 1e-6;  // metres off the receiving surface, as in the shooter
constexpr double kConverged =
    1e-12;  // Gauss-Seidel stops when no radiosity changes by more than this fraction

// The four centroids of a triangle's midpoint subdivision: a fixed, symmetric quadrature.
std::array<model::Vec3, 4> quadrature(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c) {
  const model::Vec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
  return {(a + ab + ca) / 3.0, (ab + b + bc) / 3.0, (ca + bc + c) / 3.0, (ab + bc + ca) / 3.0};
}

// The four sub-triangles of a midpoint subdivision.
std::array<std::array<model::Vec3, 3>, 4> subdivide(const model::Vec3& a, const model::Vec3& b,
                                                    const model::Vec3& c) {
  const model::Vec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
  return {{{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}};
}

// Quadrature points of a triangle after `depth` levels of midpoint subdivision: 4^(depth+1) points.
std::vector<model::Vec3> points_at_depth(const std::array<model::Vec3, 3>& t, int depth) {
  if (depth == 0) {
    const auto q = quadrature(t[0], t[1], t[2]);
    return {q.begin(), q.end()};
  }
  std::vector<model::Vec3> out;
  for (const auto& sub : subdivide(t[0], t[1], t[2])) {
    const auto inner = points_at_depth(sub, depth - 1);
    out.insert(out.end(), inner.begin(), inner.end());
  }
  return out;
}

}  // namespace

double point_polygon_form_factor(const model::Vec3& x, const model::Vec3& n,
                                 std::span<const model::Vec3> polygon) {
  // Clip to the half-space above the tangent plane (Sutherland-Hodgman), then sum the edge terms.
  std::vector<model::Vec3> clipped;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const model::Vec3& p = polygon[i];
    const model::Vec3& q = polygon[(i + 1) % polygon.size()];
    const double dp = glm::dot(p - x, n) - kHorizon, dq = glm::dot(q - x, n) - kHorizon;
    if (dp >= 0.0) clipped.push_back(p);
    if ((dp >= 0.0) != (dq >= 0.0)) clipped.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  if (clipped.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const model::Vec3 u = glm::normalize(clipped[i] - x);
    const model::Vec3 w = glm::normalize(clipped[(i + 1) % clipped.size()] - x);
    const model::Vec3 c = glm::cross(u, w);
    const double len = glm::length(c);
    if (len < 1e-15) continue;
    const double angle = std::atan2(len, glm::dot(u, w));
    sum += angle * glm::dot(n, c / len);
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

std::vector<double> reference_radiosity(const PatchSet& set, std::span<const AreaEmitter> emitters,
                                        unsigned threads, ReferenceStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t P = set.patches.size();
  const TriangleBvh bvh(set.triangles());
  auto corners = [&](std::size_t i) {
    const auto& p = set.patches[i];
    return std::array<model::Vec3, 3>{set.vertices[p.v[0]], set.vertices[p.v[1]], set.vertices[p.v[2]]};
  };

  std::vector<double> F(P * P, 0.0);
  std::atomic<std::uint64_t> rays{0};
  parallel_for(P, threads, [&](std::size_t i) {
    std::uint64_t my_rays = 0;
    {
      const auto ci = corners(i);
      // Receiver quadrature: 16 points (4 left a 3% quadrature error on the Cornell box; 16 leave under 2%).
      const auto coarse_x = points_at_depth(ci, 1);
      const auto fine_x = points_at_depth(ci, 2);    // 64
      const auto finest_x = points_at_depth(ci, 3);  // 256
      const model::Vec3& ni = set.patches[i].normal;
      const model::Vec3 centre_i = (ci[0] + ci[1] + ci[2]) / 3.0;
      const double size_i = std::sqrt(set.patches[i].area);
      for (std::size_t j = 0; j < P; ++j) {
        if (j == i) continue;
        const auto cj = corners(j);
        const model::Vec3& nj = set.patches[j].normal;
        const auto ys = quadrature(cj[0], cj[1], cj[2]);
        bool partial = false;
        // Form factor averaged over receiver points, each with its visibility of j: 4 rays, or where they
        // disagree (a penumbra) 16 rays to a finer quadrature of j.
        bool all_visible = true;
        auto average = [&](const std::vector<model::Vec3>& xs, bool trust_visible) {
          double f = 0.0;
          for (const auto& x : xs) {
            const double fx = point_polygon_form_factor(x, ni, cj);
            if (fx <= 0.0) continue;
            if (trust_visible) {
              f += fx;
              continue;
            }
            const model::Vec3 o = x + ni * kRayOffset;
            auto fraction = [&](std::span<const model::Vec3> targets) {
              int visible = 0, tried = 0;
              for (const auto& y : targets) {
                // Only targets that count in the (clipped) form factor: in front of x's tangent plane and
                // seeing x from their front side.
                if (glm::dot(x - y, nj) <= 0.0 || glm::dot(y - x, ni) <= kHorizon) continue;
                ++tried;
                ++my_rays;
                visible += !bvh.occluded(o, y - o, 0.0, 1.0 - kShortOfTarget);
              }
              return tried > 0 ? double(visible) / tried : 0.0;
            };
            double v = fraction(ys);
            all_visible = all_visible && v == 1.0;
            if (v > 0.0 && v < 1.0) {
              partial = true;
              std::vector<model::Vec3> fine;
              for (const auto& sub : subdivide(cj[0], cj[1], cj[2]))
                for (const auto& y : quadrature(sub[0], sub[1], sub[2])) fine.push_back(y);
              v = fraction(fine);
            }
            f += fx * v;
          }
          return f / xs.size();
        };
        double f = average(coarse_x, false);
        // Near neighbours: the form factor climbs steeply toward a shared edge, so integrate it over 256
        // receiver points (trusting the coarse visibility when it was complete). Penumbrae: 64 points, each
        // with its own visibility rays.
        const model::Vec3 centre_j = (cj[0] + cj[1] + cj[2]) / 3.0;
        const bool near = glm::length(centre_j - centre_i) < 2.0 * (size_i + std::sqrt(set.patches[j].area));
        if (f > 0.0 && near && all_visible && !partial)
          f = average(finest_x, true);
        else if (f > 0.0 && (partial || near))
          f = average(fine_x, false);
        F[i * P + j] = f;
      }
    }
    rays += my_rays;
  });

  std::vector<double> E(P * 3, 0.0), B;
  for (const auto& e : emitters)
    for (int c = 0; c < 3; ++c) E[e.patch * 3 + c] += e.exitance[c];
  B = E;
  std::size_t iterations = 0;
  for (double change = 1.0; change > kConverged && iterations < 100000; ++iterations) {
    change = 0.0;
    double scale = 0.0;
    for (std::size_t i = 0; i < P; ++i) {
      for (int c = 0; c < 3; ++c) {
        double gathered = 0.0;
        for (std::size_t j = 0; j < P; ++j) gathered += F[i * P + j] * B[j * 3 + c];
        const double b = E[i * 3 + c] + set.patches[i].reflectance[c] * gathered;
        change = std::max(change, std::abs(b - B[i * 3 + c]));
        scale = std::max(scale, std::abs(b));
        B[i * 3 + c] = b;
      }
    }
    change = scale > 0.0 ? change / scale : 0.0;
  }
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->iterations = iterations;
    stats->visibility_rays = rays.load();
  }
  return B;
}

}  // namespace walk::compiler
