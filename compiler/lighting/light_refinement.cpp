#include "compiler/lighting/light_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <unordered_map>
#include <unordered_set>

#include "compiler/lighting/direct_light.hpp"
#include "model/photometric_units.hpp"

namespace walk::compiler {
namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// Scalar direct irradiance (luminance weight, all circuits at full) at each point; the light per circuit
// and channel is left in `light`.
std::vector<double> irradiance(const std::vector<SurfaceSample>& points,
                               const std::vector<model::Luminaire>& luminaires, std::size_t circuits,
                               const TriangleBvh& occluders, const LightRefinementOptions& o,
                               double& shadow_rays, SparseLight& light) {
  DirectLightStats stats;
  light = direct_light(points, luminaires, circuits, occluders, {o.samples_per_luminaire, o.threads}, &stats);
  shadow_rays += double(stats.shadow_rays);
  std::vector<double> out(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const CircuitLight& e : light.row(i))
      out[i] += model::luminance_weight({e.rgb[0], e.rgb[1], e.rgb[2]});
  return out;
}

// A panel hung parallel to a surface and close in front of it (a ceiling's lamp 2 cm below it) hides the
// room from the surface along its outline: just inside the outline the surface sees the panel's back, a few
// centimetres out the whole room. The surface gets no direct light there and its indirect light is gathered
// only after meshing, so no light test can see that edge: the edges crossing the outline are split as far
// as the refinement goes. Panels hung farther off than this (metres) leave a wider, gentler edge, which the
// grid shows (the house's ceiling with its panels 0.2 m down reads smooth in the path-traced reference).
constexpr double kHungGap = 0.1;
// Surface and panel planes within this (cosine) of each other are parallel.
constexpr double kParallelCosine = 0.999;

struct HungPanel {
  model::Vec3 centre, u, v;  // u, v: unit, in the panel's plane
  double half_width, half_height;
  // Is `p` (on the surface) within the panel's outline, seen along the surface's normal?
  [[nodiscard]] bool covers(const model::Vec3& p) const {
    const model::Vec3 d = p - centre;
    return std::abs(glm::dot(d, u)) <= half_width && std::abs(glm::dot(d, v)) <= half_height;
  }
};

// The area luminaires hung close in front of each lit mesh, parallel to it and over its extent.
std::vector<std::vector<HungPanel>> hung_panels(const std::vector<PolygonMesh>& meshes,
                                                const std::vector<bool>& lit,
                                                const std::vector<model::Luminaire>& luminaires) {
  std::vector<std::vector<HungPanel>> out(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const auto& mesh = meshes[m];
    if (!lit[m] || mesh.vertices.empty()) continue;
    model::Bounds extent;
    for (const auto& p : mesh.vertices) extent.add(p);
    for (const auto& l : luminaires) {
      if (l.kind != model::LuminaireKind::Area) continue;
      const model::Vec3 n = glm::normalize(l.normal);
      const double gap = glm::dot(l.position - mesh.vertices.front(), mesh.normal);
      if (std::abs(glm::dot(n, mesh.normal)) < kParallelCosine || gap <= 0.0 || gap > kHungGap) continue;
      HungPanel h{l.position - mesh.normal * gap, glm::normalize(l.u_axis),
                  glm::normalize(glm::cross(n, l.u_axis)), 0.5 * l.width, 0.5 * l.height};
      const double reach = h.half_width + h.half_height;  // the outline lies within this of its centre
      bool near = true;
      for (int a = 0; a < 3; ++a)
        near = near && h.centre[a] + reach >= extent.min[a] && h.centre[a] - reach <= extent.max[a];
      if (near) out[m].push_back(h);
    }
  }
  return out;
}

// Does the edge from a to b cross the outline of one of `panels`?
bool crosses_outline(const std::vector<HungPanel>& panels, const model::Vec3& a, const model::Vec3& b) {
  for (const auto& h : panels)
    if (h.covers(a) != h.covers(b)) return true;
  return false;
}

// Replaces triangle t of `mesh` by its pieces for the midpoints of its marked edges (kNone: not marked);
// edge i runs from corner i to corner i + 1.
constexpr std::uint32_t kNone = ~0u;
void split_triangle(PolygonMesh& mesh, std::size_t t, const std::array<std::uint32_t, 3>& mid,
                    std::vector<std::uint32_t>& appended) {
  const std::array<std::uint32_t, 3> v{mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                                       mesh.triangles[3 * t + 2]};
  const int marked = int(mid[0] != kNone) + int(mid[1] != kNone) + int(mid[2] != kNone);
  std::vector<std::array<std::uint32_t, 3>> pieces;
  if (marked == 3) {
    pieces = {
        {v[0], mid[0], mid[2]}, {mid[0], v[1], mid[1]}, {mid[2], mid[1], v[2]}, {mid[0], mid[1], mid[2]}};
  } else if (marked == 1) {
    const int i = mid[0] != kNone ? 0 : mid[1] != kNone ? 1 : 2;
    const std::uint32_t a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3], m = mid[i];
    pieces = {{a, m, c}, {m, b, c}};
  } else if (marked == 2) {
    const int j = mid[0] == kNone ? 0 : mid[1] == kNone ? 1 : 2;  // the edge left whole: c -> a
    const std::uint32_t a = v[(j + 1) % 3], b = v[(j + 2) % 3], c = v[j];
    const std::uint32_t m0 = mid[(j + 1) % 3], m1 = mid[(j + 2) % 3];  // on a-b and b-c
    pieces.push_back({m0, b, m1});
    // The quad a, m0, m1, c along its shorter diagonal.
    const auto& p = mesh.vertices;
    if (glm::length(p[a] - p[m1]) <= glm::length(p[m0] - p[c]))
      pieces.insert(pieces.end(), {{a, m0, m1}, {a, m1, c}});
    else
      pieces.insert(pieces.end(), {{a, m0, c}, {m0, m1, c}});
  } else {
    return;
  }
  std::copy(pieces[0].begin(), pieces[0].end(), mesh.triangles.begin() + 3 * t);
  for (std::size_t k = 1; k < pieces.size(); ++k)
    appended.insert(appended.end(), pieces[k].begin(), pieces[k].end());
}

}  // namespace

LightRefinementStats refine_by_direct_light(std::vector<PolygonMesh>& meshes, const std::vector<bool>& lit,
                                            const std::vector<model::Luminaire>& luminaires,
                                            const TriangleBvh& occluders, const LightRefinementOptions& o,
                                            std::vector<SparseLight>* direct) {
  LightRefinementStats stats;
  if (direct) direct->assign(meshes.size(), {});
  if (luminaires.empty() || o.tolerance <= 0.0) return stats;
  std::size_t circuits = 1;
  for (const auto& l : luminaires) circuits = std::max<std::size_t>(circuits, l.circuit + 1);
  stats.circuits = circuits;
  // Appends the gathered light of points [first, first + count) to mesh m's.
  SparseLight light;
  auto keep = [&](std::size_t m, std::size_t first, std::size_t count) {
    if (direct)
      for (std::size_t i = first; i < first + count; ++i) (*direct)[m].append_row(light.row(i));
  };

  // Direct light at every vertex of every lit mesh, and its RMS: the scale the tolerance is relative to.
  std::vector<std::vector<double>> value(meshes.size());
  {
    std::vector<SurfaceSample> points;
    for (std::size_t m = 0; m < meshes.size(); ++m)
      if (lit[m])
        for (const auto& p : meshes[m].vertices) points.push_back({p, meshes[m].normal, model::Rgb(1.0)});
    const auto e = irradiance(points, luminaires, circuits, occluders, o, stats.shadow_rays, light);
    double square = 0.0;
    std::size_t n = 0;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      if (!lit[m]) continue;
      keep(m, n, meshes[m].vertices.size());
      for (std::size_t i = 0; i < meshes[m].vertices.size(); ++i, ++n) {
        value[m].push_back(e[n]);
        square += e[n] * e[n];
      }
    }
    const auto hung = hung_panels(meshes, lit, luminaires);
    const bool outlines = std::any_of(hung.begin(), hung.end(), [](const auto& h) { return !h.empty(); });
    if (n == 0 || (square <= 0.0 && !outlines)) return stats;
    const double allowed = o.tolerance * std::sqrt(square / double(n));

    std::size_t triangles = 0;
    for (const auto& mesh : meshes) triangles += mesh.triangles.size() / 3;
    // Memory stays bounded whatever the light does: at most this many times the diced triangles.
    constexpr std::size_t kMaxGrowth = 4;
    const std::size_t most = kMaxGrowth * triangles;

    std::vector<std::unordered_set<std::uint64_t>> settled(meshes.size());  // tested and kept whole
    for (int level = 0; level < o.max_levels && triangles < most; ++level) {
      // Every untested edge long enough to halve, with its midpoint.
      struct Edge {
        std::uint32_t mesh, a, b;
      };
      std::vector<Edge> edges;
      std::vector<SurfaceSample> midpoints;
      for (std::uint32_t m = 0; m < meshes.size(); ++m) {
        if (!lit[m]) continue;
        const auto& mesh = meshes[m];
        std::unordered_set<std::uint64_t> seen;
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
          const std::uint32_t a = mesh.triangles[i], b = mesh.triangles[i % 3 == 2 ? i - 2 : i + 1];
          const std::uint64_t key = edge_key(a, b);
          if (settled[m].count(key) || !seen.insert(key).second) continue;
          if (glm::length(mesh.vertices[a] - mesh.vertices[b]) < 2.0 * o.min_edge) {
            settled[m].insert(key);
            continue;
          }
          edges.push_back({m, a, b});
          midpoints.push_back({(mesh.vertices[a] + mesh.vertices[b]) * 0.5, mesh.normal, model::Rgb(1.0)});
        }
      }
      if (edges.empty()) break;
      stats.edges_tested += edges.size();
      const auto e = irradiance(midpoints, luminaires, circuits, occluders, o, stats.shadow_rays, light);
      std::vector<std::unordered_map<std::uint64_t, std::uint32_t>> split(meshes.size());
      for (std::size_t i = 0; i < edges.size(); ++i) {
        const auto& [m, a, b] = edges[i];
        const bool outline = crosses_outline(hung[m], meshes[m].vertices[a], meshes[m].vertices[b]);
        if (!outline && std::abs(e[i] - 0.5 * (value[m][a] + value[m][b])) <= allowed) {
          settled[m].insert(edge_key(a, b));
          continue;
        }
        stats.outline_splits += outline;
        split[m][edge_key(a, b)] = static_cast<std::uint32_t>(meshes[m].vertices.size());
        meshes[m].vertices.push_back(midpoints[i].position);
        value[m].push_back(e[i]);
        keep(m, i, 1);
        ++stats.edges_split;
      }
      std::size_t added = 0;
      for (std::size_t m = 0; m < meshes.size(); ++m) {
        if (split[m].empty()) continue;
        auto& mesh = meshes[m];
        std::vector<std::uint32_t> appended;
        const std::size_t count = mesh.triangles.size() / 3;
        for (std::size_t t = 0; t < count; ++t) {
          std::array<std::uint32_t, 3> mid{kNone, kNone, kNone};
          for (int k = 0; k < 3; ++k) {
            const auto it =
                split[m].find(edge_key(mesh.triangles[3 * t + k], mesh.triangles[3 * t + (k + 1) % 3]));
            if (it != split[m].end()) mid[k] = it->second;
          }
          split_triangle(mesh, t, mid, appended);
        }
        mesh.triangles.insert(mesh.triangles.end(), appended.begin(), appended.end());
        added += appended.size() / 3;
      }
      stats.triangles_added += added;
      triangles += added;
      stats.levels = level + 1;
      if (added == 0) break;
    }
  }
  return stats;
}

}  // namespace walk::compiler
