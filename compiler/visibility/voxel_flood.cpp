#include "compiler/visibility/voxel_flood.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "compiler/partition/axial_cover.hpp"

namespace walk::compiler {
namespace {

// Voxels are grown by this (metres) in the overlap test: a surface lying exactly on a voxel face closes the
// voxels on both sides of it, whatever the rounding of the triangle's corners.
constexpr double kTouchSlack = 1e-9;

// Are the interval [min(p), max(p)] and [-r, r] apart?
bool apart(double p0, double p1, double p2, double r) {
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangle_meets_box(const std::array<model::Vec3, 3>& triangle, const model::Vec3& centre,
                        const model::Vec3& half) {
  const model::Vec3 v0 = triangle[0] - centre, v1 = triangle[1] - centre, v2 = triangle[2] - centre;
  // The box's axes.
  for (int a = 0; a < 3; ++a)
    if (apart(v0[a], v1[a], v2[a], half[a])) return false;
  // The nine crosses of an edge with a box axis.
  const std::array<model::Vec3, 3> edges{v1 - v0, v2 - v1, v0 - v2};
  for (const auto& e : edges)
    for (int a = 0; a < 3; ++a) {
      model::Vec3 axis_dir{0.0};
      axis_dir[a] = 1.0;
      const model::Vec3 n = glm::cross(axis_dir, e);
      if (glm::dot(n, n) == 0.0) continue;  // the edge lies along the axis: the box's axes cover it
      const double r = half.x * std::abs(n.x) + half.y * std::abs(n.y) + half.z * std::abs(n.z);
      if (apart(glm::dot(n, v0), glm::dot(n, v1), glm::dot(n, v2), r)) return false;
    }
  // The triangle's plane (a degenerate triangle has none: the tests above are all it gets).
  const model::Vec3 normal = glm::cross(edges[0], edges[1]);
  const double r = half.x * std::abs(normal.x) + half.y * std::abs(normal.y) + half.z * std::abs(normal.z);
  return std::abs(glm::dot(normal, v0)) <= r;
}

int VoxelFlood::voxel_of(double x, int axis) const {
  return std::clamp(int(std::floor((x - bounds.min[axis]) / voxel)), 0, dims[axis] - 1);
}

bool VoxelFlood::reaches_beyond(const Box& face, int axis, bool max_side) const {
  if (reached.empty()) return false;
  const int u = u_axis(axis), v = v_axis(axis);
  const int layer = max_side ? dims[axis] - 1 : 0;
  for (int i = voxel_of(face.min[u], u); i <= voxel_of(face.max[u], u); ++i)
    for (int k = voxel_of(face.min[v], v); k <= voxel_of(face.max[v], v); ++k) {
      std::array<int, 3> at{};
      at[axis] = layer;
      at[u] = i;
      at[v] = k;
      if (reached[index(at[0], at[1], at[2])]) return true;
    }
  return false;
}

VoxelFlood flood_voxels(std::span<const VisPolygon> polygons, std::size_t structure, const Box& bounds,
                        std::span<const model::Vec3> seeds) {
  VoxelFlood f;
  const model::Vec3 size = bounds.size();
  f.voxel = kFloodVoxel;
  auto count = [&](double voxel) {
    double n = 1.0;
    for (int a = 0; a < 3; ++a) n *= std::ceil(size[a] / voxel) + 2.0;
    return n;
  };
  while (count(f.voxel) > double(kMaxFloodVoxels)) f.voxel *= 1.25;
  for (int a = 0; a < 3; ++a) f.dims[a] = int(std::ceil(size[a] / f.voxel)) + 2;
  f.bounds.min = bounds.min - model::Vec3(f.voxel);
  f.bounds.max = f.bounds.min + model::Vec3(f.dims[0], f.dims[1], f.dims[2]) * f.voxel;
  const std::size_t total = std::size_t(f.dims[0]) * std::size_t(f.dims[1]) * std::size_t(f.dims[2]);
  f.closed.assign(total, 0);
  f.reached.assign(total, 0);

  const model::Vec3 half(0.5 * f.voxel + kTouchSlack);
  for (std::size_t i = 0; i < std::min(structure, polygons.size()); ++i) {
    const VisPolygon& p = polygons[i];
    if (!p.opaque && !p.glass) continue;
    for (const auto& t : p.triangles) {
      const model::Vec3 lo = glm::min(t[0], glm::min(t[1], t[2])), hi = glm::max(t[0], glm::max(t[1], t[2]));
      std::array<int, 3> from{}, to{};
      for (int a = 0; a < 3; ++a) {
        from[a] = f.voxel_of(lo[a] - kTouchSlack, a);
        to[a] = f.voxel_of(hi[a] + kTouchSlack, a);
      }
      for (int z = from[2]; z <= to[2]; ++z)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int x = from[0]; x <= to[0]; ++x) {
            const std::size_t at = f.index(x, y, z);
            if (f.closed[at]) continue;
            const model::Vec3 centre = f.bounds.min + (model::Vec3(x, y, z) + 0.5) * f.voxel;
            if (triangle_meets_box(t, centre, half)) f.closed[at] = 1;
          }
    }
  }

  // Breadth first, six neighbours. The outside layer is reached but not passed along, so each opening
  // reaches only the outside beyond itself.
  std::vector<std::size_t> queue;
  for (const auto& s : seeds) {
    const std::size_t at = f.index(f.voxel_of(s.x, 0), f.voxel_of(s.y, 1), f.voxel_of(s.z, 2));
    if (f.closed[at] || f.reached[at]) continue;
    f.reached[at] = 1;
    queue.push_back(at);
  }
  const std::size_t row = std::size_t(f.dims[0]), slab = row * std::size_t(f.dims[1]);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t at = queue[head];
    const int x = int(at % row), y = int(at / row % std::size_t(f.dims[1])), z = int(at / slab);
    if (x == 0 || y == 0 || z == 0 || x + 1 == f.dims[0] || y + 1 == f.dims[1] || z + 1 == f.dims[2])
      continue;
    // Not on the outside layer: all six neighbours are in the grid.
    for (const std::size_t n : {at - 1, at + 1, at - row, at + row, at - slab, at + slab}) {
      if (f.closed[n] || f.reached[n]) continue;
      f.reached[n] = 1;
      queue.push_back(n);
    }
  }
  return f;
}

}  // namespace walk::compiler
