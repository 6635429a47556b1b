#include "compiler/visibility/open_regions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <numeric>

#include "common/parallel_for.hpp"
#include "compiler/partition/axial_cover.hpp"
#include "compiler/visibility/inside_flood.hpp"

namespace walk::compiler {
namespace {

using Grid = OpenRegions::Grid;

constexpr std::int32_t kSolid = -1;
// Points per side of the lattice that decides a voxel across a seam between solids (5: a quarter of the
// voxel apart, 5 cm at kOpenVoxel). A gap between two solids narrower than that is taken as closed: in a
// sealed Quake level solids meet exactly, and a gap that does not is a crack of a few units at most.
constexpr int kSeamLattice = 5;
constexpr std::int32_t kUnlabelled = -2;

// Lines at the cell's faces and at the axial faces of the solids meeting it, then fill lines so no gap
// passes kOpenVoxel.
Grid make_grid(const Box& box, std::span<const SolidVolume> solids) {
  Grid g;
  std::vector<double> faces[3];
  for (const auto& solid : solids) {
    if (!solid.box.overlaps(box, 0.0)) continue;
    for (int a = 0; a < 3; ++a)
      for (const double x : {solid.box.min[a], solid.box.max[a]})
        if (x > box.min[a] && x < box.max[a]) faces[a].push_back(x);
  }
  std::size_t fill_stride[3] = {1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    faces[a].push_back(box.min[a]);
    faces[a].push_back(box.max[a]);
    std::sort(faces[a].begin(), faces[a].end());
    std::vector<double> merged;
    for (const double x : faces[a])
      if (merged.empty() || x - merged.back() > kGridLineMerge) merged.push_back(x);
    if (merged.size() > 1 && box.max[a] - merged[merged.size() - 2] <= kGridLineMerge) merged.pop_back();
    merged.back() = box.max[a];
    faces[a] = std::move(merged);
  }
  // Fill lines, fewer of them while the grid would pass its cap.
  for (;;) {
    std::size_t total = 1;
    for (int a = 0; a < 3; ++a) {
      auto& lines = g.lines[a];
      lines.clear();
      for (std::size_t i = 0; i + 1 < faces[a].size(); ++i) {
        const double x0 = faces[a][i], x1 = faces[a][i + 1];
        const int parts = std::max(1, static_cast<int>(std::ceil((x1 - x0) / kOpenVoxel)));
        const int kept = std::max(1, parts / static_cast<int>(fill_stride[a]));
        for (int k = 0; k < kept; ++k) lines.push_back(x0 + (x1 - x0) * k / kept);
      }
      lines.push_back(faces[a].back());
      g.n[a] = static_cast<int>(lines.size()) - 1;
      total *= std::size_t(g.n[a]);
    }
    if (total <= kMaxVoxelsPerCell || (fill_stride[0] > 4096)) break;
    for (auto& f : fill_stride) f *= 2;
  }
  return g;
}

// Voxel index range [lo, hi] along `a` that the closed interval [x0, x1] touches, within kPlaneEpsilon:
// items and portals come from the bundle's float coordinates, solids from the model's doubles, so a face
// on a solid's boundary may lie a few micrometres inside it.
std::array<int, 2> voxel_range(const Grid& g, int a, double x0, double x1) {
  const auto& lines = g.lines[a];
  // First voxel whose upper line is at or past x0 - slack; last whose lower line is at or before x1 + slack.
  const int lo = static_cast<int>(std::lower_bound(lines.begin() + 1, lines.end(), x0 - kPlaneEpsilon) -
                                  (lines.begin() + 1));
  const int hi =
      static_cast<int>(std::upper_bound(lines.begin(), lines.end() - 1, x1 + kPlaneEpsilon) - lines.begin()) -
      1;
  return {std::clamp(lo, 0, g.n[a] - 1), std::clamp(hi, 0, g.n[a] - 1)};
}

// Voxel index range along `a` whose insides meet [x0, x1] shrunk by kPlaneEpsilon at both ends (its middle
// when narrower): a portal's outline ends on a grid line only up to the float noise between the bundle's
// coordinates and the solids', and the voxel it would touch beyond that line is another part of the cell
// (above a cornice's slanted top, the void round the level), which no sight line through the portal enters.
std::array<int, 2> voxel_range_inside(const Grid& g, int a, double x0, double x1) {
  const double mid = 0.5 * (x0 + x1);
  return {g.at(a, std::min(x0 + kPlaneEpsilon, mid)), g.at(a, std::max(x1 - kPlaneEpsilon, mid))};
}

// Do the solids of `near` hold a lattice of kSeamLattice points per side through the box [lo, hi] (one point
// along an axis it is flat in: a voxel's face)? `here` is scratch for the solids meeting the box.
bool lattice_held(const model::Vec3& lo, const model::Vec3& hi, const std::vector<const SolidVolume*>& near,
                  std::vector<const SolidVolume*>& here) {
  here.clear();
  for (const auto* solid : near)
    if (solid->box.overlaps(Box{lo, hi}, 0.0)) here.push_back(solid);
  int steps[3];
  for (int a = 0; a < 3; ++a) steps[a] = hi[a] > lo[a] ? kSeamLattice : 1;
  for (int c = 0; c < steps[0] * steps[1] * steps[2]; ++c) {
    const int at[3] = {c % steps[0], c / steps[0] % steps[1], c / (steps[0] * steps[1])};
    model::Vec3 p = lo;
    for (int a = 0; a < 3; ++a)
      if (steps[a] > 1) p[a] += (hi[a] - lo[a]) * (double(at[a]) / (kSeamLattice - 1));
    const bool held = std::any_of(here.begin(), here.end(), [&](const SolidVolume* solid) {
      return solid_contains(*solid, p, kPlaneEpsilon);
    });
    if (!held) return false;
  }
  return true;
}

// Marks solid every voxel inside one solid or, across a seam, inside their union, then labels the open
// voxels' 6-connected parts 0, 1, ... Returns how many parts.
int label_cell(Grid& g, const Box& box, std::span<const SolidVolume> solids, std::uint64_t& solid_voxels) {
  g.region.assign(std::size_t(g.n[0]) * std::size_t(g.n[1]) * std::size_t(g.n[2]), kUnlabelled);
  // Grid corners inside some solid: where solids meet along a slanted face, a voxel across the seam lies in
  // no one solid, but in their union (tested below).
  const std::size_t px = std::size_t(g.n[0]) + 1, py = std::size_t(g.n[1]) + 1;
  std::vector<char> covered(px * py * (std::size_t(g.n[2]) + 1), 0);
  auto corner = [&](int i, int j, int k) {
    return (std::size_t(k) * py + std::size_t(j)) * px + std::size_t(i);
  };
  // Voxel faces one solid holds (its four corners), per axis, indexed by the face's lowest corner: open
  // voxels on either side of such a face do not join through it. Where a sloping ceiling meets a wall's top
  // edge, the room below and the gap above touch only along that edge, but a voxel across the edge holds
  // both; its faces towards the gap lie in the solids, so the two stay apart.
  std::array<std::vector<char>, 3> blocked;
  for (auto& b : blocked) b.assign(covered.size(), 0);
  std::vector<const SolidVolume*> near;
  std::vector<char> inside;
  for (const auto& solid : solids) {
    if (!solid.box.overlaps(box, 0.0)) continue;
    near.push_back(&solid);
    // Grid corners within the solid's box, and which of them the solid holds.
    int lo[3], hi[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      const auto& lines = g.lines[a];
      lo[a] = static_cast<int>(
          std::lower_bound(lines.begin(), lines.end(), solid.box.min[a] - kGridLineMerge) - lines.begin());
      hi[a] =
          static_cast<int>(std::upper_bound(lines.begin(), lines.end(), solid.box.max[a] + kGridLineMerge) -
                           lines.begin()) -
          1;
      empty = empty || hi[a] - lo[a] < 1;
    }
    if (empty) continue;
    const int m[3] = {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
    inside.assign(std::size_t(m[0]) * std::size_t(m[1]) * std::size_t(m[2]), 0);
    auto at = [&](int i, int j, int k) {
      return (std::size_t(k) * std::size_t(m[1]) + std::size_t(j)) * std::size_t(m[0]) + std::size_t(i);
    };
    for (int k = 0; k < m[2]; ++k)
      for (int j = 0; j < m[1]; ++j)
        for (int i = 0; i < m[0]; ++i) {
          const model::Vec3 p{g.lines[0][std::size_t(lo[0] + i)], g.lines[1][std::size_t(lo[1] + j)],
                              g.lines[2][std::size_t(lo[2] + k)]};
          inside[at(i, j, k)] = solid_contains(solid, p, kPlaneEpsilon) ? 1 : 0;
          if (inside[at(i, j, k)]) covered[corner(lo[0] + i, lo[1] + j, lo[2] + k)] = 1;
        }
    // A convex solid holds a face when it holds its four corners.
    for (int k = 0; k < m[2]; ++k)
      for (int j = 0; j < m[1]; ++j)
        for (int i = 0; i < m[0]; ++i) {
          if (!inside[at(i, j, k)]) continue;
          const int c[3] = {i, j, k};
          for (int a = 0; a < 3; ++a) {
            const int u = (a + 1) % 3, v = (a + 2) % 3;
            if (c[u] + 1 >= m[u] || c[v] + 1 >= m[v]) continue;
            int cu[3] = {i, j, k}, cv[3] = {i, j, k}, cuv[3] = {i, j, k};
            ++cu[u];
            ++cv[v];
            ++cuv[u];
            ++cuv[v];
            if (inside[at(cu[0], cu[1], cu[2])] && inside[at(cv[0], cv[1], cv[2])] &&
                inside[at(cuv[0], cuv[1], cuv[2])])
              blocked[std::size_t(a)][corner(lo[0] + i, lo[1] + j, lo[2] + k)] = 1;
          }
        }
    // A convex solid holds a voxel when it holds its eight corners.
    for (int k = 0; k + 1 < m[2]; ++k)
      for (int j = 0; j + 1 < m[1]; ++j)
        for (int i = 0; i + 1 < m[0]; ++i) {
          bool all = true;
          for (int c = 0; c < 8 && all; ++c)
            all = inside[at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))] != 0;
          if (all) g.region[g.index(lo[0] + i, lo[1] + j, lo[2] + k)] = kSolid;
        }
  }
  // A voxel whose corners all lie in solids but in no one of them: solid when a finer lattice of points
  // through it (kSeamLattice per side) lies in solids too.
  std::vector<const SolidVolume*> here;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        auto& r = g.region[g.index(i, j, k)];
        if (r == kSolid) continue;
        bool corners = true;
        for (int c = 0; c < 8 && corners; ++c)
          corners = covered[corner(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))] != 0;
        if (!corners) continue;
        const model::Vec3 lo{g.lines[0][std::size_t(i)], g.lines[1][std::size_t(j)],
                             g.lines[2][std::size_t(k)]};
        const model::Vec3 hi{g.lines[0][std::size_t(i) + 1], g.lines[1][std::size_t(j) + 1],
                             g.lines[2][std::size_t(k) + 1]};
        if (lattice_held(lo, hi, near, here)) r = kSolid;
      }
  // A face whose corners all lie in solids but in no one of them: closed when a kSeamLattice² lattice of
  // points on it lies in solids too (two wedges meeting along a slanted seam across it).
  auto seam_closed = [&](int a, const int f[3]) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int c = 0; c < 4; ++c) {
      int q[3] = {f[0], f[1], f[2]};
      q[u] += c & 1;
      q[v] += c >> 1;
      if (!covered[corner(q[0], q[1], q[2])]) return false;
    }
    model::Vec3 lo, hi;
    for (int b = 0; b < 3; ++b) {
      lo[b] = g.lines[b][std::size_t(f[b])];
      hi[b] = b == a ? lo[b] : g.lines[b][std::size_t(f[b]) + 1];
    }
    return lattice_held(lo, hi, near, here);
  };
  int parts = 0;
  std::vector<std::array<int, 3>> stack;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        if (g.region[g.index(i, j, k)] == kSolid) ++solid_voxels;
        if (g.region[g.index(i, j, k)] != kUnlabelled) continue;
        g.region[g.index(i, j, k)] = parts;
        stack.push_back({i, j, k});
        while (!stack.empty()) {
          const auto v = stack.back();
          stack.pop_back();
          // Neighbours along z first, x last: the stack pops x's next, so the fill runs along rows of
          // consecutive voxels rather than across planes a grid's slice apart (a cache miss each).
          // The neighbour's and the shared face's coordinates are computed whole, not by writing one
          // element of a copy: reading the copy back after a one-element store stalled the store buffer
          // (a third of this function's samples under perf on E1M1).
          for (int d = 5; d >= 0; --d) {
            const int a = d / 2;
            const bool up = d % 2 != 0;
            const int step = up ? 1 : -1;
            const int x = v[0] + (a == 0 ? step : 0), y = v[1] + (a == 1 ? step : 0),
                      z = v[2] + (a == 2 ? step : 0);
            if (x < 0 || y < 0 || z < 0 || x >= g.n[0] || y >= g.n[1] || z >= g.n[2]) continue;
            auto& r = g.region[g.index(x, y, z)];
            if (r != kUnlabelled) continue;
            // The shared face's lowest corner: the far voxel's when stepping up the axis, else this one's.
            const int f[3] = {up ? x : v[0], up ? y : v[1], up ? z : v[2]};
            if (blocked[std::size_t(a)][corner(f[0], f[1], f[2])]) continue;
            if (seam_closed(a, f)) continue;
            r = parts;
            stack.push_back({x, y, z});
          }
        }
        ++parts;
      }
  return parts;
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// The parts of `cell`'s grid on its face `axis` (the +axis face when `max_side`) within [lo, hi] in the
// face's two in-plane axes.
void parts_on_face(const Grid& g, int axis, bool max_side, const model::Vec3& lo, const model::Vec3& hi,
                   std::vector<int>& out) {
  out.clear();
  const int u = u_axis(axis), v = v_axis(axis);
  const auto ru = voxel_range(g, u, lo[u], hi[u]);
  const auto rv = voxel_range(g, v, lo[v], hi[v]);
  int idx[3];
  idx[axis] = max_side ? g.n[axis] - 1 : 0;
  for (int b = rv[0]; b <= rv[1]; ++b)
    for (int a = ru[0]; a <= ru[1]; ++a) {
      idx[u] = a;
      idx[v] = b;
      const std::int32_t r = g.region[g.index(idx[0], idx[1], idx[2])];
      if (r >= 0 && std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
    }
}

// The parts of `cell`'s grid under portal `p`'s open area on its face `axis` (the +axis face when
// `max_side`): row by row of the face's voxels, the outline's pieces within the row and the voxels their
// extent along the row spans. The outline's box would take in parts beside an L-shaped or ring-shaped
// opening that no sight line through it reaches, and join them into one region.
void parts_under_portal(const Grid& g, const Portal& p, bool max_side, std::vector<int>& out) {
  out.clear();
  const int axis = p.axis, u = u_axis(axis), v = v_axis(axis);
  ClipperLib::Paths outline;
  Box row{model::Vec3{1e300}, model::Vec3{-1e300}};
  for (const auto& w : p.outline) {
    auto& path = outline.emplace_back();
    for (const auto& q : w) {
      path.push_back(axial_point(q[u], q[v]));
      row.min = glm::min(row.min, q);
      row.max = glm::max(row.max, q);
    }
  }
  if (outline.empty()) return;
  const auto rv = voxel_range_inside(g, v, row.min[v], row.max[v]);
  int idx[3];
  idx[axis] = max_side ? g.n[axis] - 1 : 0;
  for (int b = rv[0]; b <= rv[1]; ++b) {
    row.min[v] = g.lines[v][std::size_t(b)];
    row.max[v] = g.lines[v][std::size_t(b) + 1];
    ClipperLib::Clipper clip;
    clip.AddPaths(outline, ClipperLib::ptSubject, true);
    clip.AddPath(rect_path(row, axis), ClipperLib::ptClip, true);
    ClipperLib::Paths pieces;
    clip.Execute(ClipperLib::ctIntersection, pieces, ClipperLib::pftEvenOdd, ClipperLib::pftNonZero);
    idx[v] = b;
    for (const auto& piece : pieces) {
      ClipperLib::cInt a0 = piece.front().X, a1 = piece.front().X;
      for (const auto& q : piece) {
        a0 = std::min(a0, q.X);
        a1 = std::max(a1, q.X);
      }
      const auto ru =
          voxel_range_inside(g, u, double(a0) / kAxialClipperScale, double(a1) / kAxialClipperScale);
      for (int a = ru[0]; a <= ru[1]; ++a) {
        idx[u] = a;
        const std::int32_t r = g.region[g.index(idx[0], idx[1], idx[2])];
        if (r >= 0 && std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
      }
    }
  }
}

}  // namespace

OpenRegions open_regions(const Partition& part, const PortalGraph& graph,
                         const std::vector<VisPolygon>& polygons, std::span<const SolidVolume> solids,
                         unsigned threads) {
  OpenRegions o;
  const std::size_t n = part.cells.size();
  o.grids.resize(n);
  std::vector<int> parts(n);
  std::vector<std::uint64_t> solid_voxels(n, 0);
  parallel_for(n, threads, [&](std::size_t c) {
    o.grids[c] = make_grid(part.cells[c], solids);
    parts[c] = label_cell(o.grids[c], part.cells[c], solids, solid_voxels[c]);
  });
  for (std::size_t c = 0; c < n; ++c) {
    o.voxels += o.grids[c].region.size();
    o.solid_voxels += solid_voxels[c];
  }
  // A portal joins the parts under its open area on each side; parts it meets twice on one side are one
  // region.
  std::vector<std::vector<int>> parent(n);
  for (std::size_t c = 0; c < n; ++c) {
    parent[c].resize(std::size_t(parts[c]));
    std::iota(parent[c].begin(), parent[c].end(), 0);
  }
  std::vector<std::array<int, 2>> portal_part(graph.portals.size(), {-1, -1});
  std::vector<int> met;
  for (std::size_t id = 0; id < graph.portals.size(); ++id) {
    const Portal& p = graph.portals[id];
    for (int side = 0; side < 2; ++side) {
      const std::uint32_t c = side == 0 ? p.back : p.front;
      parts_under_portal(o.grids[c], p, side == 0, met);
      for (const int r : met) parent[c][find_root(parent[c], r)] = find_root(parent[c], met.front());
      if (!met.empty()) portal_part[id][side] = met.front();
    }
  }
  // Regions: the merged parts, numbered cell by cell.
  o.regions_of.resize(n);
  std::vector<std::vector<std::int32_t>> region_of_part(n);
  for (std::size_t c = 0; c < n; ++c) {
    region_of_part[c].assign(parent[c].size(), -1);
    for (int r = 0; r < int(parent[c].size()); ++r) {
      auto& id = region_of_part[c][std::size_t(find_root(parent[c], r))];
      if (id < 0) {
        id = static_cast<std::int32_t>(o.cell_of.size());
        o.cell_of.push_back(static_cast<std::uint32_t>(c));
        o.regions_of[c].push_back(static_cast<std::uint32_t>(id));
      }
    }
    for (int r = 0; r < int(parent[c].size()); ++r)
      region_of_part[c][std::size_t(r)] = region_of_part[c][std::size_t(find_root(parent[c], r))];
  }
  const std::size_t regions = o.cell_of.size();
  Partition& rp = o.partition;
  rp.bounds = part.bounds;
  rp.planes = part.planes;
  rp.depth = part.depth;
  rp.candidates = part.candidates;
  rp.cells.assign(regions, Box{model::Vec3{1e300}, model::Vec3{-1e300}});
  rp.cell_polygons.resize(regions);
  // Cells touching each cell: an item lying on a face the cell shares with a neighbour may be listed in the
  // neighbour only (a detail cluster whose box rests on it), yet be seen from this cell's side.
  std::vector<std::vector<std::uint32_t>> touching(n);
  for (std::uint32_t c = 0; c < n; ++c)
    for (std::uint32_t d = c + 1; d < n; ++d)
      if (part.cells[c].overlaps(part.cells[d], kPlaneEpsilon)) {
        touching[c].push_back(d);
        touching[d].push_back(c);
      }
  parallel_for(n, threads, [&](std::size_t c) {
    Grid& g = o.grids[c];
    for (auto& r : g.region)
      if (r >= 0) r = region_of_part[c][std::size_t(r)];
    // Region boxes, from their voxels.
    for (int k = 0; k < g.n[2]; ++k)
      for (int j = 0; j < g.n[1]; ++j)
        for (int i = 0; i < g.n[0]; ++i) {
          const std::int32_t r = g.region[g.index(i, j, k)];
          if (r < 0) continue;
          Box& b = rp.cells[std::size_t(r)];
          const model::Vec3 lo{g.lines[0][std::size_t(i)], g.lines[1][std::size_t(j)],
                               g.lines[2][std::size_t(k)]};
          const model::Vec3 hi{g.lines[0][std::size_t(i) + 1], g.lines[1][std::size_t(j) + 1],
                               g.lines[2][std::size_t(k) + 1]};
          b.min = glm::min(b.min, lo);
          b.max = glm::max(b.max, hi);
        }
    for (const auto r : o.regions_of[c]) {
      rp.cells[r].min = glm::max(rp.cells[r].min, part.cells[c].min);
      rp.cells[r].max = glm::min(rp.cells[r].max, part.cells[c].max);
    }
    // Items: each region whose voxels their box touches.
    std::vector<std::int32_t> touched;
    std::vector<std::uint32_t> items = part.cell_polygons[c];
    for (const auto d : touching[c])
      for (const auto item : part.cell_polygons[d])
        if (polygons[item].box.overlaps(part.cells[c], kPlaneEpsilon)) items.push_back(item);
    std::sort(items.begin(), items.end());
    items.erase(std::unique(items.begin(), items.end()), items.end());
    for (const auto item : items) {
      const Box& box = polygons[item].box;
      std::array<int, 2> range[3];
      for (int a = 0; a < 3; ++a) range[a] = voxel_range(g, a, box.min[a], box.max[a]);
      touched.clear();
      for (int k = range[2][0]; k <= range[2][1]; ++k)
        for (int j = range[1][0]; j <= range[1][1]; ++j)
          for (int i = range[0][0]; i <= range[0][1]; ++i) {
            const std::int32_t r = g.region[g.index(i, j, k)];
            if (r >= 0 && std::find(touched.begin(), touched.end(), r) == touched.end()) touched.push_back(r);
          }
      for (const auto r : touched) rp.cell_polygons[std::size_t(r)].push_back(item);
    }
  });
  // Portals between regions.
  PortalGraph& rg = o.graph;
  rg.cell_portals.resize(regions);
  for (std::size_t id = 0; id < graph.portals.size(); ++id) {
    const Portal& p = graph.portals[id];
    if (portal_part[id][0] < 0 || portal_part[id][1] < 0) {
      ++o.portals_dropped;
      continue;
    }
    Portal q = p;
    q.back = static_cast<std::uint32_t>(region_of_part[p.back][std::size_t(portal_part[id][0])]);
    q.front = static_cast<std::uint32_t>(region_of_part[p.front][std::size_t(portal_part[id][1])]);
    const auto rid = static_cast<std::uint32_t>(rg.portals.size());
    rg.cell_portals[q.back].push_back(rid);
    rg.cell_portals[q.front].push_back(rid);
    rg.portals.push_back(std::move(q));
  }
  // Leaks: in the region next to their place on the boundary.
  for (const Leak& leak : graph.leaks) {
    parts_on_face(o.grids[leak.cell], leak.axis, leak.max_side, leak.where, leak.where, met);
    if (met.empty()) continue;  // wholly against a solid
    Leak l = leak;
    l.cell = static_cast<std::uint32_t>(met.front());
    rg.leaks.push_back(l);
  }
  return o;
}

int OpenRegions::Grid::at(int a, double x) const {
  const int i =
      static_cast<int>(std::upper_bound(lines[a].begin(), lines[a].end(), x) - lines[a].begin()) - 1;
  return std::clamp(i, 0, n[a] - 1);
}

std::uint32_t OpenRegions::locate(std::uint32_t cell, const model::Vec3& p) const {
  if (cell >= grids.size()) return kOutside;
  const Grid& g = grids[cell];
  const int at[3] = {g.at(0, p.x), g.at(1, p.y), g.at(2, p.z)};
  for (int radius = 0; radius <= 2; ++radius)
    for (int dz = -radius; dz <= radius; ++dz)
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int x = at[0] + dx, y = at[1] + dy, z = at[2] + dz;
          if (x < 0 || y < 0 || z < 0 || x >= g.n[0] || y >= g.n[1] || z >= g.n[2]) continue;
          const std::int32_t r = g.region[g.index(x, y, z)];
          if (r >= 0) return static_cast<std::uint32_t>(r);
        }
  return kOutside;
}

bool OpenRegions::holds(std::uint32_t region, const model::Vec3& p) const {
  const Grid& g = grids[cell_of[region]];
  return g.region[g.index(g.at(0, p.x), g.at(1, p.y), g.at(2, p.z))] == static_cast<std::int32_t>(region);
}

std::vector<std::uint32_t> void_facing_items(const OpenRegions& regions, const Partition& cells,
                                             const std::vector<VisPolygon>& polygons,
                                             const std::vector<char>& inside) {
  const PortalGraph& g = regions.graph;
  const std::size_t n = regions.cell_of.size();
  std::vector<char> outside(n, 0);
  std::vector<std::uint32_t> openings;
  for (const Leak& leak : g.leaks)
    if (leak.cell < n && !outside[leak.cell]) {
      outside[leak.cell] = 1;
      openings.push_back(leak.cell);
    }
  std::vector<std::uint32_t> out;
  if (openings.empty()) return out;
  flood_portals(g, outside, std::move(openings), [](const Portal&) { return true; });
  for (std::uint32_t item = 0; item < polygons.size(); ++item) {
    const VisPolygon& p = polygons[item];
    if (p.detail || !p.opaque) continue;
    bool walk = false, void_seen = false;
    for (const auto& t : p.triangles) {
      const model::Vec3 facing = glm::cross(t[1] - t[0], t[2] - t[0]);
      if (glm::length(facing) <= 0.0) continue;
      const model::Vec3 probe = (t[0] + t[1] + t[2]) / 3.0 + kVoidProbe * glm::normalize(facing);
      if (!cells.bounds.contains(probe)) {  // out of the model's box: the outside
        void_seen = true;
        continue;
      }
      const std::uint32_t cell = locate(cells.nodes, probe);
      const std::uint32_t region = regions.locate(cell, probe);
      if (region >= n || !regions.holds(region, probe)) continue;
      walk = walk || inside[region];
      void_seen = void_seen || (outside[region] && !inside[region]);
      if (walk) break;
    }
    if (void_seen && !walk) out.push_back(item);
  }
  return out;
}

}  // namespace walk::compiler
