#include "compiler/partition/partition.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "compiler/partition/axial_cover.hpp"

namespace walk::compiler {
namespace {

// A polygon whose extent on the axis reaches past the plane by more than this is split by it (metres:
// far above float rounding, far below any wall).
constexpr double kSideTolerance = 1e-4;
// A plane at least this fraction wall (its occlusion term) splits a cell whatever its priority: a wall
// between rooms near a cell's side leaves few polygons beyond it, and the balance term alone kept a top
// storey of the generated M building (18 x 12 m, its rooms, their walls and the outside beyond them) one
// cell, its best plane 60 % wall at priority 0.58. Half: most of the section is wall, the rest doorways.
constexpr double kDividingWall = 0.5;
// ... when it leaves at least this much room on each side (metres): a wall between rooms, not one of the
// faces a cluttered level has every few decimetres. Without it E1M1 got slabs of cells 0.4 m thick, and a
// pixel seen through one's portal was missed at `walk verify`'s CI size (cause not traced).
constexpr double kDividingWallRoom = 1.0;

Box bounds_of(const std::vector<VisPolygon>& polygons) {
  model::Bounds b;
  for (const auto& p : polygons)
    if (!p.triangles.empty()) {
      b.add(p.box.min);
      b.add(p.box.max);
    }
  if (b.empty()) return {};
  return {b.min, b.max};
}

}  // namespace

std::vector<AxialPlane> axial_planes(const std::vector<VisPolygon>& polygons) {
  std::vector<std::pair<std::pair<int, double>, std::uint32_t>> keyed;
  for (std::uint32_t i = 0; i < polygons.size(); ++i)
    if (polygons[i].axis >= 0 && (polygons[i].opaque || polygons[i].glass))
      keyed.push_back({{polygons[i].axis, polygons[i].coord}, i});
  std::sort(keyed.begin(), keyed.end());
  std::vector<AxialPlane> out;
  for (const auto& [key, id] : keyed) {
    if (out.empty() || out.back().axis != key.first || key.second - out.back().coord > kInPlaneTolerance)
      out.push_back({key.first, key.second, {}, {}});
    (polygons[id].opaque ? out.back().opaque : out.back().glass).push_back(id);
  }
  return out;
}

const AxialPlane* find_plane(const std::vector<AxialPlane>& planes, int axis, double coord) {
  auto it = std::lower_bound(planes.begin(), planes.end(), std::make_pair(axis, coord - kInPlaneTolerance),
                             [](const AxialPlane& p, const std::pair<int, double>& k) {
                               return std::make_pair(p.axis, p.coord) < k;
                             });
  if (it != planes.end() && it->axis == axis && std::abs(it->coord - coord) <= kInPlaneTolerance) return &*it;
  return nullptr;
}

double occlusion_fraction(const AxialPlane& plane, const Box& cell, const std::vector<VisPolygon>& polygons) {
  const int u = u_axis(plane.axis), v = v_axis(plane.axis);
  const double rect = (cell.max[u] - cell.min[u]) * (cell.max[v] - cell.min[v]);
  if (rect <= 0.0 || plane.opaque.empty()) return 0.0;
  return std::clamp(area_of(union_of(plane.opaque, polygons, plane.axis, &cell)) / rect, 0.0, 1.0);
}

PlaneScore score_plane(const AxialPlane& plane, const Box& cell,
                       const std::vector<std::uint32_t>& cell_polygons,
                       const std::vector<VisPolygon>& polygons, const VisibilityConfig& config,
                       double needed) {
  PlaneScore s;
  std::size_t front = 0, back = 0, split = 0;
  std::size_t counted = 0;
  for (const auto id : cell_polygons) {
    if (polygons[id].detail) continue;  // detail never shapes cells
    ++counted;
    const auto& b = polygons[id].box;
    const bool ahead = b.max[plane.axis] > plane.coord + kSideTolerance;
    const bool behind = b.min[plane.axis] < plane.coord - kSideTolerance;
    if (ahead && behind)
      ++split;
    else if (ahead)
      ++front;
    else if (behind)
      ++back;
  }
  const double f = double(front + split), k = double(back + split);
  s.balance = f + k > 0.0 ? 1.0 - std::abs(f - k) / (f + k) : 0.0;
  s.split = counted == 0 ? 1.0 : 1.0 - double(split) / double(counted);
  const double rest = config.w_balance * s.balance + config.w_split * s.split;
  if (config.w_occlusion + rest > needed) s.occlusion = occlusion_fraction(plane, cell, polygons);
  s.priority = config.w_occlusion * s.occlusion + config.w_balance * s.balance + config.w_split * s.split;
  return s;
}

Partition build_partition(const std::vector<VisPolygon>& polygons, const VisibilityConfig& config) {
  Partition part;
  part.bounds = bounds_of(polygons);
  part.planes = axial_planes(polygons);
  part.candidates = part.planes.size();
  std::vector<std::uint32_t> all;
  for (std::uint32_t i = 0; i < polygons.size(); ++i)
    if (!polygons[i].triangles.empty()) all.push_back(i);

  // Returns the child reference: node index, or -cell-1 for a leaf.
  std::function<std::int32_t(const Box&, std::vector<std::uint32_t>, int)> build =
      [&](const Box& box, std::vector<std::uint32_t> ids, int depth) -> std::int32_t {
    part.depth = std::max(part.depth, depth);
    const AxialPlane* best = nullptr;
    PlaneScore best_score;
    if (depth < config.max_depth) {
      for (const auto& plane : part.planes) {
        if (plane.coord < box.min[plane.axis] + config.min_cell_size ||
            plane.coord > box.max[plane.axis] - config.min_cell_size)
          continue;
        // Until a plane qualifies, the occlusion of every plane with room on both sides is wanted: one that
        // is mostly wall qualifies whatever its priority.
        const bool room = plane.coord - box.min[plane.axis] >= kDividingWallRoom &&
                          box.max[plane.axis] - plane.coord >= kDividingWallRoom;
        const PlaneScore s = score_plane(plane, box, ids, polygons, config,
                                         best   ? best_score.priority
                                         : room ? -1.0
                                                : config.threshold);
        const bool dividing = room && s.occlusion >= kDividingWall;
        const bool qualifies = s.priority > config.threshold || dividing;
        if (qualifies && (!best || s.priority > best_score.priority)) {
          best = &plane;
          best_score = s;
        }
      }
    }
    if (!best) {
      spdlog::debug(
          "partition: leaf at depth {} box ({:.2f} {:.2f} {:.2f})..({:.2f} {:.2f} {:.2f}), {} polygons",
          depth, box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z, ids.size());
      part.cells.push_back(box);
      part.cell_polygons.push_back(std::move(ids));
      return -static_cast<std::int32_t>(part.cells.size());
    }
    spdlog::debug(
        "partition: depth {} split axis {} at {:.3f}: occlusion {:.2f} balance {:.2f} split {:.2f} -> {:.3f}",
        depth, best->axis, best->coord, best_score.occlusion, best_score.balance, best_score.split,
        best_score.priority);
    const auto node = static_cast<std::int32_t>(part.nodes.size());
    model::NodeRecord rec{};
    rec.plane[best->axis] = 1.0;
    rec.plane[3] = -best->coord;
    part.nodes.push_back(rec);
    const int axis = best->axis;
    const double c = best->coord;
    Box front_box = box, back_box = box;
    front_box.min[axis] = c;
    back_box.max[axis] = c;
    std::vector<std::uint32_t> front_ids, back_ids;
    for (const auto id : ids) {
      // A polygon belongs to each side it reaches into. One that only touches the plane along an edge (a
      // ground-floor wall under the upper storey's floor) belongs to its own side alone: listing it above
      // too put every wall below into the PVS of every cell that sees the storey above. One lying in the
      // plane belongs to both sides: seen from behind it is still seen (single-sided walls, back-face
      // culling off).
      const VisPolygon& p = polygons[id];
      const bool reaches_front = p.box.max[axis] > c + kSideTolerance;
      const bool reaches_back = p.box.min[axis] < c - kSideTolerance;
      const bool in_plane = !reaches_front && !reaches_back;
      if (reaches_front || in_plane) front_ids.push_back(id);
      if (reaches_back || in_plane) back_ids.push_back(id);
    }
    ids.clear();
    ids.shrink_to_fit();
    const std::int32_t f = build(front_box, std::move(front_ids), depth + 1);
    part.nodes[node].front = f;
    const std::int32_t b = build(back_box, std::move(back_ids), depth + 1);
    part.nodes[node].back = b;
    return node;
  };
  const std::int32_t root = build(part.bounds, std::move(all), 0);
  if (root < 0) part.nodes.clear();  // single cell: no tree
  return part;
}

std::uint32_t locate(const std::vector<model::NodeRecord>& nodes, const model::Vec3& p) {
  if (nodes.empty()) return 0;
  std::int32_t node = 0;
  while (node >= 0) {
    const auto& n = nodes[static_cast<std::size_t>(node)];
    const double side = n.plane[0] * p.x + n.plane[1] * p.y + n.plane[2] * p.z + n.plane[3];
    node = side >= 0.0 ? n.front : n.back;
  }
  return static_cast<std::uint32_t>(-node - 1);
}

}  // namespace walk::compiler
