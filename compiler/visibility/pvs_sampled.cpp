#include "compiler/visibility/pvs_sampled.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {
namespace {

model::Vec3 random_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 2.0 * u(rng) - 1.0;
  const double phi = 2.0 * std::numbers::pi * u(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace

template <class Rng>
model::Vec3 random_point_in(const Winding& w, Rng& rng) {
  if (w.size() < 3) return w.empty() ? model::Vec3{0.0} : w.front();
  std::vector<double> cum;
  double total = 0.0;
  for (std::size_t i = 1; i + 1 < w.size(); ++i) {
    total += glm::length(glm::cross(w[i] - w[0], w[i + 1] - w[0]));
    cum.push_back(total);
  }
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (total <= 0.0) return w.front();
  const std::size_t t = std::min<std::size_t>(
      std::lower_bound(cum.begin(), cum.end(), u(rng) * total) - cum.begin(), cum.size() - 1);
  double a = u(rng), b = u(rng);
  if (a + b > 1.0) {
    a = 1.0 - a;
    b = 1.0 - b;
  }
  return w[0] + (w[t + 1] - w[0]) * a + (w[t + 2] - w[0]) * b;
}
template model::Vec3 random_point_in(const Winding&, std::mt19937_64&);

std::vector<std::vector<std::uint32_t>> sampled_pvs(const Partition& part, const PortalGraph& graph,
                                                    const std::vector<VisPolygon>& polygons,
                                                    const RayCaster& caster, const SampledPvsOptions& options,
                                                    std::uint64_t* rays) {
  std::vector<char> glass(polygons.size());
  for (std::size_t i = 0; i < polygons.size(); ++i) glass[i] = polygons[i].glass;
  std::vector<std::vector<std::uint32_t>> out(part.cells.size());
  std::atomic<std::uint64_t> cast{0};
  Progress progress("cells: sampled views", part.cells.size(), "cells");
  parallel_for(part.cells.size(), options.threads, [&](std::size_t c) {
    progress.advance();
    if (!options.cells.empty() && !options.cells[c]) return;
    std::mt19937_64 rng(options.seed * 0x9E3779B97F4A7C15ull + c);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<char> seen(polygons.size(), 0);
    std::vector<std::uint32_t> ids;
    const Box& box = part.cells[c];
    // Points on portals aim out of the cell: only portals open that way (a one-way portal the other way is
    // a wall's front seen from this side).
    std::vector<std::uint32_t> portals;
    for (const auto id : graph.cell_portals[c])
      if (graph.portals[id].open_from(static_cast<std::uint32_t>(c))) portals.push_back(id);
    for (int i = 0; i < options.points; ++i) {
      model::Vec3 origin;
      model::Vec3 out_normal{0.0};  // points on a portal aim out of the cell through it
      if (i % 2 == 1 && !portals.empty()) {
        const Portal& p = graph.portals[portals[rng() % portals.size()]];
        origin = random_point_in(p.hull, rng);
        out_normal = p.out_of(static_cast<std::uint32_t>(c)).n;
      } else {
        bool found = false;
        for (int tries = 0; tries < kSampleTries && !found; ++tries) {
          for (int a = 0; a < 3; ++a) origin[a] = box.min[a] + u(rng) * (box.max[a] - box.min[a]);
          found = !options.usable || options.usable(c, origin);
        }
        if (!found) continue;
      }
      cast += std::uint64_t(options.rays_per_point);
      for (int r = 0; r < options.rays_per_point; ++r) {
        Ray ray;
        ray.origin = origin;
        ray.dir = random_direction(rng);
        if (glm::dot(ray.dir, out_normal) < 0.0) ray.dir = -ray.dir;
        ids.clear();
        trace_through_glass(caster, ray, glass, ids, options.cull_back_faces);
        for (const auto id : ids)
          if (id < seen.size()) seen[id] = 1;
      }
    }
    for (std::uint32_t p = 0; p < seen.size(); ++p)
      if (seen[p]) out[c].push_back(p);
  });
  if (rays) *rays = cast;
  return out;
}

}  // namespace walk::compiler
