#include "compiler/geometry/openings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "compiler/geometry/clipper_convert.hpp"
#include "compiler/geometry/plane_frame.hpp"
#include "compiler/geometry/polygon_tree.hpp"

namespace walk::compiler {
namespace {

using ClipperLib::Path;
using ClipperLib::Paths;

// Overlap below this (square metres) is two faces merely touching along an edge, not an opening in a wall.
constexpr double kMinOverlapArea = 1e-6;

bool is_cutter(model::Role role) {
  return role == model::Role::Opening || role == model::Role::Glass;
}

model::Bounds bounds_of(const model::Polygon& p) {
  model::Bounds b;
  for (const auto& v : p.vertices) b.add(v);
  return b;
}

bool boxes_touch(const model::Bounds& a, const model::Bounds& b, double slack) {
  for (int i = 0; i < 3; ++i) {
    if (a.min[i] > b.max[i] + slack || b.min[i] > a.max[i] + slack) return false;
  }
  return true;
}

// Clipper paths are positive (counter-clockwise) for a union with the non-zero rule to add them up.
void make_positive(Path& path) {
  if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
}

// An opaque face that may receive cut-outs, in its own plane's frame.
struct Host {
  std::size_t index = 0;
  PlaneFrame frame;
  PointMap points{frame};
  Paths paths;  // outer boundary and existing holes
  model::Bounds box;
  std::vector<std::size_t> cutters;  // indices into the cutter list, once assigned
};

// Cutters by the cells of a uniform grid their boxes (grown by their depth) overlap, so a face finds the
// cutters it may host without a look at every one: the generated L building has 4,000 cutters and 5 M faces.
class CutterGrid {
 public:
  void add(std::uint32_t cutter, const model::Bounds& grown) {
    for_cells(grown, [&](std::uint64_t key) { cells_[key].push_back(cutter); });
  }
  // f(cutter) for each cutter in a cell `box` overlaps; a cutter may come more than once. A box over more
  // cells than hold cutters (a site's ground plane) is given every cutter instead.
  template <class F>
  void for_each_near(const model::Bounds& box, F&& f) const {
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) cells *= double(cell_of(box.max[a]) - cell_of(box.min[a]) + 1);
    if (cells > double(cells_.size())) {
      for (const auto& [key, cutters] : cells_)
        for (const std::uint32_t k : cutters) f(k);
      return;
    }
    for_cells(box, [&](std::uint64_t key) {
      if (const auto it = cells_.find(key); it != cells_.end())
        for (const std::uint32_t k : it->second) f(k);
    });
  }

 private:
  // A door's size: a wall or floor spans a few hundred cells, a furniture triangle one to eight.
  static constexpr double kCellMetres = 2.0;
  // Cell coordinates are clamped to 21 bits a side (+-2,000 km at 2 m), packed into one key.
  static constexpr std::int64_t kCellRange = 1 << 20;
  static std::int64_t cell_of(double x) {
    if (std::isnan(x)) return 0;  // the cleanup stage drops such faces; kept out of the cast here
    return std::clamp<std::int64_t>(std::int64_t(std::floor(x / kCellMetres)), -kCellRange, kCellRange - 1);
  }
  template <class F>
  static void for_cells(const model::Bounds& box, F&& f) {
    std::array<std::int64_t, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = cell_of(box.min[a]);
      hi[a] = cell_of(box.max[a]);
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          f(std::uint64_t(x + kCellRange) << 42 | std::uint64_t(y + kCellRange) << 21 |
            std::uint64_t(z + kCellRange));
  }
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

// How a cutter sits on a host: its distance from the host's plane, or nothing when it is not parallel to it,
// too far from it, or does not overlap it.
std::optional<double> placement(Host& host, const model::Polygon& cutter, double tolerance, double depth) {
  double lo = 1e300, hi = -1e300;
  for (const auto& v : cutter.vertices) {
    const double d = host.frame.distance(v);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  // Parallel within `tolerance` (all corners at the same distance) and no further than `depth` away.
  if (hi - lo > tolerance || std::max(std::abs(lo), std::abs(hi)) > depth) return std::nullopt;
  Path path = host.points.to_path(cutter.vertices);
  if (path.size() < 3) return std::nullopt;
  make_positive(path);
  ClipperLib::Clipper overlap;
  overlap.AddPaths(host.paths, ClipperLib::ptSubject, true);
  overlap.AddPath(path, ClipperLib::ptClip, true);
  Paths common;
  overlap.Execute(ClipperLib::ctIntersection, common, ClipperLib::pftEvenOdd, ClipperLib::pftNonZero);
  double area = 0.0;
  for (const auto& p : common) area += area_m2(p);
  const bool coplanar = std::max(std::abs(lo), std::abs(hi)) <= tolerance;
  // Coplanar faces need only overlap; a recessed window must lie wholly within its wall.
  const double needed = coplanar ? kMinOverlapArea : area_m2(path) - kMinOverlapArea;
  if (std::abs(area) < needed) return std::nullopt;
  return 0.5 * (lo + hi);
}

}  // namespace

OpeningStats cut_openings(model::Model& model, double tolerance) {
  OpeningStats stats;
  std::vector<std::size_t> cutters;
  for (std::size_t i = 0; i < model.polygons.size(); ++i) {
    if (is_cutter(model.polygons[i].role)) cutters.push_back(i);
  }
  // Hosts: the opaque faces whose box touches a cutter's (grown by its depth), each with the cutters it
  // touches as (cutter, host) pairs, hosts in face order.
  const auto depth_of = [&](std::size_t k) {
    return model.polygons[cutters[k]].role == model::Role::Glass ? std::max(tolerance, kGlassInsetDepth)
                                                                 : tolerance;
  };
  std::vector<model::Bounds> cutter_boxes(cutters.size());
  CutterGrid grid;
  for (std::size_t k = 0; k < cutters.size(); ++k) {
    cutter_boxes[k] = bounds_of(model.polygons[cutters[k]]);
    model::Bounds grown = cutter_boxes[k];
    for (int a = 0; a < 3; ++a) {
      grown.min[a] -= depth_of(k);
      grown.max[a] += depth_of(k);
    }
    grid.add(std::uint32_t(k), grown);
  }
  std::vector<Host> hosts;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (cutter, host)
  std::vector<std::uint32_t> near;
  for (std::size_t h = 0; h < model.polygons.size() && !cutters.empty(); ++h) {
    const model::Polygon& polygon = model.polygons[h];
    if (polygon.role != model::Role::Opaque) continue;
    const model::Bounds box = bounds_of(polygon);
    near.clear();
    grid.for_each_near(box, [&](std::uint32_t k) {
      if (boxes_touch(box, cutter_boxes[k], depth_of(k))) near.push_back(k);
    });
    PlaneFrame frame;
    if (near.empty() || !plane_frame(polygon.vertices, frame)) continue;
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (const std::uint32_t k : near) pairs.emplace_back(k, std::uint32_t(hosts.size()));
    Host host{h, frame, PointMap(frame), {}, box, {}};
    host.paths.push_back(host.points.to_path(polygon.vertices));
    for (const auto& hole : polygon.holes) host.paths.push_back(host.points.to_path(hole));
    hosts.push_back(std::move(host));
  }
  std::sort(pairs.begin(), pairs.end());

  // Each cutter goes to the hosts nearest its plane: coplanar walls (every zone's copy of a partition) or,
  // for glass only, the wall it is recessed behind.
  std::vector<bool> matched(cutters.size(), false);
  auto pair = pairs.begin();
  for (std::size_t k = 0; k < cutters.size(); ++k) {
    const model::Polygon& cutter = model.polygons[cutters[k]];
    std::vector<std::pair<double, Host*>> found;
    for (; pair != pairs.end() && pair->first == k; ++pair) {
      Host& host = hosts[pair->second];
      if (const auto d = placement(host, cutter, tolerance, depth_of(k)))
        found.emplace_back(std::abs(*d), &host);
    }
    if (found.empty()) continue;
    double nearest = found.front().first;
    for (const auto& [d, host] : found) nearest = std::min(nearest, d);
    bool inset = false;
    for (const auto& [d, host] : found) {
      if (d > nearest + tolerance) continue;
      host->cutters.push_back(k);
      inset = inset || d > tolerance;
    }
    matched[k] = true;
    if (inset) ++stats.glass_inset;
  }

  // What each cut host turns into (possibly nothing, when openings cover it whole).
  std::vector<bool> was_cut(model.polygons.size(), false);
  std::vector<std::vector<model::Polygon>> pieces(model.polygons.size());
  for (auto& host : hosts) {
    if (host.cutters.empty()) continue;
    Paths cuts;
    for (std::size_t k : host.cutters) {
      Path path = host.points.to_path(model.polygons[cutters[k]].vertices);  // projected onto the host
      make_positive(path);
      cuts.push_back(std::move(path));
    }
    ++stats.hosts_cut;
    was_cut[host.index] = true;
    ClipperLib::Clipper clipper;
    clipper.AddPaths(host.paths, ClipperLib::ptSubject, true);
    clipper.AddPaths(cuts, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    // Even-odd for the host (outer boundary plus its holes, whatever their winding), non-zero for the union
    // of overlapping cut-outs (a door and its copy from the zone on the other side of the wall).
    clipper.Execute(ClipperLib::ctDifference, tree, ClipperLib::pftEvenOdd, ClipperLib::pftNonZero);
    const model::Polygon& original = model.polygons[host.index];
    for (auto& piece : polygons_from_tree(tree, host.points)) {
      model::Polygon out = original;
      out.vertices = std::move(piece.vertices);
      out.holes = std::move(piece.holes);
      pieces[host.index].push_back(std::move(out));
    }
  }
  // Rebuild in the original order: cut hosts become their pieces, glass stays, openings stay only when no
  // wall took them.
  std::vector<bool> drop(model.polygons.size(), false);
  for (std::size_t k = 0; k < cutters.size(); ++k) {
    const bool opening = model.polygons[cutters[k]].role == model::Role::Opening;
    if (matched[k]) stats.frame_groups.push_back(model.polygons[cutters[k]].group);
    if (!matched[k]) {
      ++stats.unmatched;
    } else if (opening) {
      ++stats.openings_cut;
      drop[cutters[k]] = true;
    } else {
      ++stats.glass_cut;
    }
  }
  std::sort(stats.frame_groups.begin(), stats.frame_groups.end());
  stats.frame_groups.erase(std::unique(stats.frame_groups.begin(), stats.frame_groups.end()),
                           stats.frame_groups.end());
  std::vector<model::Polygon> result;
  result.reserve(model.polygons.size() + stats.hosts_cut);
  for (std::size_t i = 0; i < model.polygons.size(); ++i) {
    if (drop[i]) continue;
    if (!was_cut[i]) {
      result.push_back(std::move(model.polygons[i]));
      continue;
    }
    for (auto& piece : pieces[i]) result.push_back(std::move(piece));
  }
  model.polygons = std::move(result);
  return stats;
}

}  // namespace walk::compiler
