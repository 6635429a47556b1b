#include "compiler/visibility/verify_visibility.hpp"

#include <algorithm>
#include <bit>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <optional>
#include <random>

#include "common/parallel_for.hpp"
#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {
namespace {

// Viewpoints keep this far (metres) inside their cell, so the tree puts them in it and not on a face.
constexpr double kInset = 1e-3;
// Random draws per viewpoint to find one in open space before the cell is looked at from anywhere.
constexpr int kFreeSpaceTries = 64;

// A uniform number in (0, 1) from a 64-bit state (splitmix64), advancing it.
double unit(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double(z >> 11) + 0.5) * 0x1.0p-53;
}

// Cube face f: forward, right, up (right x up = forward, the usual cube map frames).
void face_frame(int f, model::Vec3& fwd, model::Vec3& right, model::Vec3& up) {
  const int axis = f / 2;
  const double s = (f % 2) ? -1.0 : 1.0;
  fwd = model::Vec3{0.0};
  fwd[axis] = s;
  right = model::Vec3{0.0};
  right[(axis + 1) % 3] = s;
  up = glm::cross(fwd, right);
}

// Where viewpoints may stand: the cell kInset inside each face (a quarter of a thinner side).
Box inset(const Box& b) {
  Box r = b;
  for (int a = 0; a < 3; ++a) {
    const double margin = std::min(kInset, 0.25 * (b.max[a] - b.min[a]));
    r.min[a] += margin;
    r.max[a] -= margin;
  }
  return r;
}

model::Vec3 inset_point(const Box& b, const model::Vec3& t) {
  const Box in = inset(b);
  return in.min + t * (in.max - in.min);
}

}  // namespace

VisibilityJudge::VisibilityJudge(std::span<const model::VertexRecord> vertices,
                                 std::span<const std::uint32_t> indices,
                                 std::span<const model::PolygonRecord> polygons, const VerifyOptions& options,
                                 std::span<const std::uint32_t> void_facing)
    : options_(options), polygons_(vis_polygons(vertices, indices, polygons)) {
  std::vector<Triangle> triangles;
  glass_.resize(polygons_.size());
  void_facing_.assign(polygons_.size(), 0);
  for (const auto p : void_facing)
    if (p < void_facing_.size()) void_facing_[p] = 1;
  for (std::uint32_t p = 0; p < polygons_.size(); ++p) {
    glass_[p] = polygons_[p].glass;
    for (const auto& t : polygons_[p].triangles) triangles.push_back({t[0], t[1], t[2], p});
  }
  caster_ = make_ray_caster(options.ray_caster, triangles);
}

void VisibilityJudge::cube(const model::Vec3& eye, int res, CellViews* keep, std::vector<char>& seen) const {
  const std::size_t n = std::size_t(res) * std::size_t(res);
  // Each eye's pixels get their own sample positions.
  const std::uint64_t salt = options_.seed * 0x9E3779B97F4A7C15ull ^ std::bit_cast<std::uint64_t>(eye.x) ^
                             std::rotl(std::bit_cast<std::uint64_t>(eye.y), 21) ^
                             std::rotl(std::bit_cast<std::uint64_t>(eye.z), 42);
  if (keep) keep->eyes.emplace_back(eye, keep->offsets.size() - 1);
  for (int f = 0; f < 6; ++f) {
    model::Vec3 fwd, right, up;
    face_frame(f, fwd, right, up);
    std::vector<std::vector<std::uint32_t>> rows(static_cast<std::size_t>(res));
    std::vector<std::vector<std::uint32_t>> row_offsets(static_cast<std::size_t>(res));
    parallel_for(static_cast<std::size_t>(res), options_.threads, [&](std::size_t y) {
      auto& ids = rows[y];
      for (int x = 0; x < res; ++x) {
        Ray ray;
        ray.origin = eye;
        double jx = 0.5, jy = 0.5;
        if (options_.jitter) {
          std::uint64_t h = salt ^ (std::uint64_t(f) << 58 | std::uint64_t(y) << 29 | std::uint64_t(x));
          jx = unit(h);
          jy = unit(h);
        }
        ray.dir = fwd + right * ((2.0 * (x + jx)) / res - 1.0) + up * ((2.0 * (double(y) + jy)) / res - 1.0);
        trace_through_glass(*caster_, ray, glass_, ids, options_.cull_back_faces);
        row_offsets[y].push_back(static_cast<std::uint32_t>(ids.size()));
      }
    });
    for (std::size_t y = 0; y < rows.size(); ++y) {
      for (const auto id : rows[y]) seen[id] = 1;
      if (keep) {
        const auto base = static_cast<std::uint32_t>(keep->ids.size());
        keep->ids.insert(keep->ids.end(), rows[y].begin(), rows[y].end());
        for (const auto o : row_offsets[y]) keep->offsets.push_back(base + o);
      }
    }
  }
  (void)n;
}

std::vector<model::Vec3> portal_viewpoints(const PortalGraph& graph, const Box& cell,
                                           std::uint32_t cell_index) {
  std::vector<model::Vec3> eyes;
  if (cell_index >= graph.cell_portals.size()) return eyes;
  for (const auto id : graph.cell_portals[cell_index]) {
    const Portal& portal = graph.portals[id];
    if (portal.hull.empty()) continue;
    model::Vec3 centre{0.0};
    for (const auto& v : portal.hull) centre += v;
    centre /= double(portal.hull.size());
    std::vector<model::Vec3> points{centre};
    const std::size_t corners = std::min<std::size_t>(kPortalCorners, portal.hull.size());
    for (std::size_t k = 0; k < corners; ++k) {
      const model::Vec3& v = portal.hull[k * portal.hull.size() / corners];
      points.push_back(v + (centre - v) * 0.1);
    }
    // Into the cell, off the face the portal lies on, and within the inset box like every other viewpoint.
    const double into = -kInset * portal.out_of(cell_index).n[portal.axis];
    const Box in = inset(cell);
    for (auto p : points) {
      p[portal.axis] = portal.coord + into;
      eyes.push_back(glm::clamp(p, in.min, in.max));
    }
  }
  return eyes;
}

BundleCells bundle_cells(const std::vector<VisPolygon>& polygons, std::span<const model::CellRecord> cells,
                         bool cull_back_faces) {
  BundleCells out;
  Partition& part = out.partition;
  part.planes = axial_planes(polygons);
  model::Bounds bounds;
  for (const auto& c : cells) {
    Box box{{c.bounds_min[0], c.bounds_min[1], c.bounds_min[2]},
            {c.bounds_max[0], c.bounds_max[1], c.bounds_max[2]}};
    bounds.add(box.min);
    bounds.add(box.max);
    part.cells.push_back(box);
  }
  part.bounds = {bounds.min, bounds.max};
  part.cell_polygons.resize(part.cells.size());
  out.graph = find_portals(part, polygons, cull_back_faces);
  return out;
}

CellViews VisibilityJudge::views(const Box& cell, std::uint32_t cell_index,
                                 std::span<const model::Vec3> portal_eyes) const {
  CellViews v;
  std::vector<char> seen(glass_.size(), 0);
  std::mt19937_64 rng(options_.seed * 0x9E3779B97F4A7C15ull + cell_index);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto usable = [&](const model::Vec3& p) { return !options_.free_space_only || in_free_space(p); };
  // A cell whose open space is a sliver beside a portal (a niche, the gap beside a pillar) holds no point
  // that random draws find, but its portal viewpoints stand in it: it is judged from those.
  std::optional<bool> open_beside_portals;
  for (int i = 0; i < options_.viewpoints; ++i) {
    // Up to kFreeSpaceTries draws for a point in open space; a cell with none (all solid, or a model
    // without closed rooms) is still looked at, from anywhere in it, and reported.
    model::Vec3 eye = inset_point(cell, {u(rng), u(rng), u(rng)});
    bool open = v.no_free_space || usable(eye);
    for (int tries = 1; !open && tries < kFreeSpaceTries; ++tries) {
      eye = inset_point(cell, {u(rng), u(rng), u(rng)});
      open = usable(eye);
    }
    if (!open && options_.portal_views) {
      if (!open_beside_portals)
        open_beside_portals = std::any_of(portal_eyes.begin(), portal_eyes.end(), usable);
      if (*open_beside_portals) break;
    }
    if (!open) v.no_free_space = true;
    cube(eye, options_.resolution, &v, seen);
  }
  const int d = options_.dense;
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j)
      for (int k = 0; k < d; ++k) {
        const model::Vec3 eye = inset_point(cell, {(i + 0.5) / d, (j + 0.5) / d, (k + 0.5) / d});
        if (v.no_free_space || usable(eye)) cube(eye, options_.dense_resolution, nullptr, seen);
      }
  if (options_.portal_views)
    for (const auto& eye : portal_eyes)
      if (v.no_free_space || usable(eye)) {
        cube(eye, options_.dense_resolution, &v, seen);
        ++v.portal_viewpoints;
      }
  for (std::uint32_t p = 0; p < seen.size(); ++p)
    if (seen[p]) v.exact.push_back(p);
  return v;
}

bool VisibilityJudge::in_free_space(const model::Vec3& p) const {
  int front = 0, back = 0;
  for (int k = 0; k < 14; ++k) {
    Ray ray;
    ray.origin = p;
    if (k < 6) {
      ray.dir = model::Vec3{0.0};
      ray.dir[k / 2] = k % 2 ? -1.0 : 1.0;
    } else {
      ray.dir = {k & 1 ? -1.0 : 1.0, k & 2 ? -1.0 : 1.0, k & 4 ? -1.0 : 1.0};
    }
    // The first opaque polygon on the sight line: glass is passed through (it may face either way).
    std::vector<std::uint32_t> ids;
    const RayHit stop = trace_through_glass(*caster_, ray, glass_, ids);
    if (stop.hit() && !glass_[stop.polygon]) (stop.front && !void_facing_[stop.polygon] ? front : back) += 1;
  }
  return front > back;
}

std::uint64_t VisibilityJudge::missed(const CellViews& views, const std::vector<std::uint32_t>& pvs) const {
  std::vector<char> in(glass_.size(), 0);
  for (const auto p : pvs)
    if (p < in.size()) in[p] = 1;
  std::uint64_t missed = 0;
  for (std::size_t px = 0; px + 1 < views.offsets.size(); ++px)
    for (std::uint32_t i = views.offsets[px]; i < views.offsets[px + 1]; ++i)
      if (!in[views.ids[i]]) {
        ++missed;
        break;
      }
  return missed;
}

std::vector<bool> cells_to_judge(const std::vector<bool>& no_open_space) {
  const bool open_somewhere =
      std::find(no_open_space.begin(), no_open_space.end(), false) != no_open_space.end();
  std::vector<bool> judge(no_open_space.size());
  for (std::size_t c = 0; c < judge.size(); ++c) judge[c] = !open_somewhere || !no_open_space[c];
  return judge;
}

std::vector<std::uint32_t> cluster_of_polygons(std::size_t polygons,
                                               std::span<const model::ClusterRecord> clusters,
                                               std::span<const std::uint32_t> cluster_polygons) {
  std::vector<std::uint32_t> out(polygons, kNoCluster);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const std::uint64_t first = clusters[c].polygon_first;
    const std::uint64_t end =
        std::min<std::uint64_t>(first + clusters[c].polygon_count, cluster_polygons.size());
    for (std::uint64_t i = first; i < end; ++i)
      if (cluster_polygons[i] < polygons) out[cluster_polygons[i]] = static_cast<std::uint32_t>(c);
  }
  return out;
}

std::uint64_t clusters_holding(std::span<const std::uint32_t> ids,
                               std::span<const std::uint32_t> cluster_of) {
  std::vector<std::uint32_t> clusters;
  for (const auto p : ids)
    if (p < cluster_of.size() && cluster_of[p] != kNoCluster) clusters.push_back(cluster_of[p]);
  std::sort(clusters.begin(), clusters.end());
  return std::uint64_t(std::unique(clusters.begin(), clusters.end()) - clusters.begin());
}

void summarise(VerifyReport& r) {
  r.missed = r.pixels = 0;
  std::uint64_t pvs = 0, exact = 0, pvs_clusters = 0, exact_clusters = 0;
  r.pvs_worst = 0;
  r.ratio_worst = r.cluster_ratio_worst = 0.0;
  for (const auto& row : r.rows) {
    r.missed += row.missed;
    r.pixels += row.pixels;
    pvs += row.pvs;
    exact += row.exact;
    pvs_clusters += row.pvs_clusters;
    exact_clusters += row.exact_clusters;
    r.pvs_worst = std::max(r.pvs_worst, row.pvs);
    if (row.exact > 0) r.ratio_worst = std::max(r.ratio_worst, double(row.pvs) / double(row.exact));
    if (row.exact_clusters > 0)
      r.cluster_ratio_worst =
          std::max(r.cluster_ratio_worst, double(row.pvs_clusters) / double(row.exact_clusters));
  }
  const double n = std::max<double>(1.0, double(r.rows.size()));
  r.pvs_average = double(pvs) / n;
  r.exact_average = double(exact) / n;
  r.ratio = exact > 0 ? double(pvs) / double(exact) : 0.0;
  r.cluster_pvs_average = double(pvs_clusters) / n;
  r.cluster_exact_average = double(exact_clusters) / n;
  r.cluster_ratio = exact_clusters > 0 ? double(pvs_clusters) / double(exact_clusters) : 0.0;
  r.reduction = r.pvs_average > 0.0 ? double(r.polygons) / r.pvs_average : 0.0;
}

}  // namespace walk::compiler
