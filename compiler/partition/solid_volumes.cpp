#include "compiler/partition/solid_volumes.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "compiler/partition/axial_cover.hpp"

namespace walk::compiler {
namespace {

// A face whose Newell vector is shorter than this (m^2, twice its area) has no plane: a sliver the brush
// builder welded away.
constexpr double kMinFaceArea = 1e-12;

}  // namespace

std::vector<SolidVolume> solid_volumes(std::span<const model::Solid> solids) {
  std::vector<SolidVolume> out;
  out.reserve(solids.size());
  for (const auto& solid : solids) {
    SolidVolume v;
    v.box = {model::Vec3{1e300}, model::Vec3{-1e300}};
    for (const auto& face : solid.faces) {
      const model::Vec3 a = model::area_vector(face);
      if (glm::length(a) <= kMinFaceArea) continue;
      const model::Vec3 n = glm::normalize(a);
      v.planes.push_back({n, -glm::dot(n, face.front())});
      v.faces.push_back(face);
      for (const auto& p : face) {
        v.box.min = glm::min(v.box.min, p);
        v.box.max = glm::max(v.box.max, p);
      }
    }
    if (v.planes.size() >= 4) out.push_back(std::move(v));
  }
  return out;
}

bool solid_contains(const SolidVolume& solid, const model::Vec3& p, double tolerance) {
  return std::all_of(solid.planes.begin(), solid.planes.end(),
                     [&](const Plane& plane) { return plane.distance(p) <= tolerance; });
}

ClipperLib::Path solid_section(const SolidVolume& solid, int axis, double coord) {
  if (coord < solid.box.min[axis] || coord > solid.box.max[axis]) return {};
  const int u = u_axis(axis), v = v_axis(axis);
  // Where the edges cross the plane, and the corners on it: the section is their convex hull.
  std::vector<model::Vec3> points;
  for (const auto& face : solid.faces)
    for (std::size_t i = 0; i < face.size(); ++i) {
      const model::Vec3& a = face[i];
      const model::Vec3& b = face[(i + 1) % face.size()];
      const double da = a[axis] - coord, db = b[axis] - coord;
      if (da == 0.0) points.push_back(a);
      if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) points.push_back(a + (b - a) * (da / (da - db)));
    }
  model::Vec3 normal{0.0};
  normal[axis] = 1.0;
  const Winding hull = convex_hull(points, normal);
  if (hull.size() < 3) return {};
  ClipperLib::Path path;
  for (const auto& p : hull) path.push_back(axial_point(p[u], p[v]));
  if (ClipperLib::Area(path) == 0.0) return {};
  if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
  return path;
}

}  // namespace walk::compiler
