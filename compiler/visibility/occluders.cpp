#include "compiler/visibility/occluders.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <utility>

namespace walk::compiler {
namespace {

bool inside(const Occluder& o, const model::Vec3& q) {
  for (const Plane& e : o.edges)
    if (e.distance(q) < kPlaneEpsilon) return false;
  return true;
}

}  // namespace

std::optional<Occluder> make_occluder(Winding outline, const model::Vec3& normal) {
  if (outline.size() < 3) return std::nullopt;
  Occluder o;
  o.plane = {normal, -glm::dot(normal, outline[0])};
  o.area = winding_area(outline, normal);
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const model::Vec3& a = outline[i];
    const model::Vec3 e = outline[(i + 1) % outline.size()] - a;
    const double len = glm::length(e);
    if (!(len > 0.0)) return std::nullopt;
    // Counter-clockwise about the normal: inside is on the left of each edge, along cross(normal, e).
    const model::Vec3 m = glm::cross(normal, e) / len;
    o.edges.push_back({m, -glm::dot(m, a)});
  }
  o.outline = std::move(outline);
  return o;
}

std::vector<std::vector<Occluder>> cell_occluders(const Partition& part,
                                                  const std::vector<VisPolygon>& polygons) {
  std::vector<std::vector<Occluder>> out(part.cells.size());
  for (std::size_t c = 0; c < part.cells.size(); ++c) {
    for (const auto p : part.cell_polygons[c]) {
      const VisPolygon& vp = polygons[p];
      if (!vp.opaque || glm::length(vp.normal) == 0.0) continue;
      auto o = make_occluder(vp.hull, vp.normal);
      if (!o) continue;
      bool planar = true;
      for (const auto& t : vp.triangles)
        for (const auto& v : t) planar = planar && std::abs(o->plane.distance(v)) <= kPlaneEpsilon;
      if (!planar || o->area < kMinOccluderArea || !fills_hull(vp)) continue;
      out[c].push_back(std::move(*o));
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
  for (const auto& t : target) {
    const double d = o.plane.distance(t);
    if (!(d * side < 0.0) || std::abs(d) < kPlaneEpsilon) return false;
  }
  // No allocation: the flow asks this for every polygon and portal it reaches.
  for (const auto& l : light) {
    const double dl = o.plane.distance(l);
    for (const auto& t : target) {
      const model::Vec3 q = l + (t - l) * (dl / (dl - o.plane.distance(t)));  // where the segment crosses
      if (!inside(o, q)) return false;
    }
  }
  return true;
}

}  // namespace walk::compiler
