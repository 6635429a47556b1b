#include "compiler/visibility/occluders.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

// Area of a planar winding (m^2).
double area(const Winding& w, const model::Vec3& normal) {
  model::Vec3 sum(0.0);
  for (std::size_t i = 0; i < w.size(); ++i) sum += glm::cross(w[i], w[(i + 1) % w.size()]);
  return 0.5 * std::abs(glm::dot(sum, normal));
}

// A polygon fills its hull when their areas agree to this fraction (the hull of a polygon with a notch or
// a hole is larger by the notch's or hole's area).
constexpr double kConvexArea = 1e-6;

bool inside(const Occluder& o, const model::Vec3& q) {
  for (std::size_t i = 0; i < o.outline.size(); ++i) {
    const model::Vec3& a = o.outline[i];
    const model::Vec3& b = o.outline[(i + 1) % o.outline.size()];
    const model::Vec3 e = b - a;
    const double len = glm::length(e);
    if (!(len > 0.0)) return false;
    // Distance of q inside the edge's line, in the plane (counter-clockwise winding: inside is on the left).
    if (glm::dot(glm::cross(e, q - a), o.plane.n) / len < kPlaneEpsilon) return false;
  }
  return true;
}

}  // namespace

std::vector<std::vector<Occluder>> cell_occluders(const Partition& part,
                                                  const std::vector<VisPolygon>& polygons) {
  std::vector<std::vector<Occluder>> out(part.cells.size());
  for (std::size_t c = 0; c < part.cells.size(); ++c) {
    for (const auto p : part.cell_polygons[c]) {
      const VisPolygon& vp = polygons[p];
      if (!vp.opaque || vp.hull.size() < 3 || glm::length(vp.normal) == 0.0) continue;
      const Plane plane{vp.normal, -glm::dot(vp.normal, vp.hull[0])};
      double tri_area = 0.0;
      bool planar = true;
      for (const auto& t : vp.triangles) {
        tri_area += 0.5 * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
        for (const auto& v : t) planar = planar && std::abs(plane.distance(v)) <= kPlaneEpsilon;
      }
      const double hull_area = area(vp.hull, vp.normal);
      if (!planar || hull_area < kMinOccluderArea || std::abs(hull_area - tri_area) > kConvexArea * hull_area)
        continue;
      out[c].push_back({vp.hull, plane, hull_area});
    }
    auto& list = out[c];
    std::sort(list.begin(), list.end(), [](const Occluder& a, const Occluder& b) { return a.area > b.area; });
    if (list.size() > kMaxOccludersPerCell) list.resize(kMaxOccludersPerCell);
  }
  return out;
}

bool hidden_by(const Winding& target, const Winding& light, const Occluder& o, bool cull_back_faces) {
  if (target.empty() || light.empty()) return false;
  // Light strictly on one side of the occluder's plane (its front when back faces are culled), the target
  // strictly on the other.
  double side = 0.0;
  for (const auto& l : light) {
    const double d = o.plane.distance(l);
    if (std::abs(d) < kPlaneEpsilon || (side != 0.0 && (d > 0.0) != (side > 0.0))) return false;
    side = d;
  }
  if (cull_back_faces && side < 0.0) return false;
  std::vector<double> dt(target.size());
  for (std::size_t j = 0; j < target.size(); ++j) {
    dt[j] = o.plane.distance(target[j]);
    if (!(dt[j] * side < 0.0) || std::abs(dt[j]) < kPlaneEpsilon) return false;
  }
  for (const auto& l : light) {
    const double dl = o.plane.distance(l);
    for (std::size_t j = 0; j < target.size(); ++j) {
      const model::Vec3 q = l + (target[j] - l) * (dl / (dl - dt[j]));  // where the segment crosses the plane
      if (!inside(o, q)) return false;
    }
  }
  return true;
}

}  // namespace walk::compiler
