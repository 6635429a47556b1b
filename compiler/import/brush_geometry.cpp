#include "compiler/import/brush_geometry.hpp"

#include <cmath>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

using model::Vec3;

// Points closer than this to collinear (|cross| relative to the product of the two edge lengths: the sine
// of the angle between them) give no plane: 1e-9 rad is far below the angle any editor produces.
constexpr double kMinPlaneSine = 1e-9;
// Normals whose dot product exceeds this are parallel (for duplicate planes): an angle of ~1.4e-5 rad, which
// moves a point 4096 units away by 0.06 units: coincident at the weld scale near the origin, and so a
// duplicate in all but pathological files.
constexpr double kParallelDot = 1.0 - 1e-10;

std::vector<Vec3> base_winding(const BrushPlane& p) {
  // Major axis of the normal picks the "up" vector, as qbsp's BaseWindingForPlane does.
  const Vec3 n = p.normal;
  const Vec3 up = (std::abs(n.z) >= std::abs(n.x) && std::abs(n.z) >= std::abs(n.y)) ? Vec3(1.0, 0.0, 0.0)
                                                                                     : Vec3(0.0, 0.0, 1.0);
  const Vec3 v = glm::normalize(up - n * glm::dot(up, n)) * kBaseWinding;
  const Vec3 u = glm::cross(v, n);  // (u, v, n) right-handed: corners below run counter-clockwise about n
  const Vec3 o = n * p.dist;
  return {o - u - v, o + u - v, o + u + v, o - u + v};
}

}  // namespace

bool plane_from_points(const std::array<Vec3, 3>& p, BrushPlane& out) {
  const Vec3 a = p[0] - p[1], b = p[2] - p[1];
  const Vec3 n = glm::cross(a, b);
  const double len = glm::length(n);
  if (!(len > kMinPlaneSine * glm::length(a) * glm::length(b)) || !std::isfinite(len)) return false;
  out.normal = n / len;
  // Axial planes are kept exactly axial: their coordinates then stay the integers the file gave.
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(out.normal[axis]) > 1.0 - 1e-15) {
      out.normal = Vec3(0.0);
      out.normal[axis] = n[axis] > 0.0 ? 1.0 : -1.0;
    }
  }
  out.dist = glm::dot(out.normal, p[1]);
  return true;
}

std::vector<Vec3> clip_winding(const std::vector<Vec3>& winding, const BrushPlane& plane,
                               std::vector<Vec3>* front) {
  const std::size_t n = winding.size();
  std::vector<double> d(n);
  std::vector<int> side(n);
  bool any_front = false, any_back = false;
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = glm::dot(plane.normal, winding[i]) - plane.dist;
    side[i] = d[i] > kClipEpsilon ? 1 : (d[i] < -kClipEpsilon ? -1 : 0);
    any_front = any_front || side[i] > 0;
    any_back = any_back || side[i] < 0;
  }
  if (!any_front) {
    if (front) front->clear();
    return winding;
  }
  if (!any_back) {
    if (front) *front = winding;
    return {};
  }
  std::vector<Vec3> back_out, front_out;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = winding[i];
    if (side[i] <= 0) back_out.push_back(p);
    if (side[i] >= 0) front_out.push_back(p);
    const std::size_t j = (i + 1) % n;
    if (side[i] == 0 || side[j] == 0 || side[i] == side[j]) continue;
    const double t = d[i] / (d[i] - d[j]);
    Vec3 mid = p + (winding[j] - p) * t;
    for (int axis = 0; axis < 3; ++axis) {  // exact on axial planes, as qbsp does
      if (plane.normal[axis] == 1.0) mid[axis] = plane.dist;
      if (plane.normal[axis] == -1.0) mid[axis] = -plane.dist;
    }
    back_out.push_back(mid);
    front_out.push_back(mid);
  }
  if (front) *front = std::move(front_out);
  return back_out;
}

bool build_brush(const std::vector<std::array<Vec3, 3>>& plane_points, ConvexBrush& out, BrushStats& stats) {
  out = {};
  std::vector<bool> usable(plane_points.size(), false);
  out.planes.resize(plane_points.size());
  for (std::size_t i = 0; i < plane_points.size(); ++i) {
    if (!plane_from_points(plane_points[i], out.planes[i])) {
      ++stats.degenerate_planes;
      continue;
    }
    usable[i] = true;
    for (std::size_t j = 0; j < i; ++j) {
      if (usable[j] && glm::dot(out.planes[i].normal, out.planes[j].normal) > kParallelDot &&
          std::abs(out.planes[i].dist - out.planes[j].dist) <= kClipEpsilon) {
        usable[i] = false;
        ++stats.duplicate_planes;
        break;
      }
    }
  }
  // Faces by clipping each plane's huge square by every other plane.
  std::vector<BrushFace> faces;
  for (std::size_t i = 0; i < out.planes.size(); ++i) {
    if (!usable[i]) continue;
    std::vector<Vec3> w = base_winding(out.planes[i]);
    for (std::size_t j = 0; j < out.planes.size() && !w.empty(); ++j) {
      if (j == i || !usable[j]) continue;
      // A plane parallel and coincident with this one (opposite facing) would cut the face away entirely
      // by round-off: the brush has no thickness there and is empty anyway.
      w = clip_winding(w, out.planes[j]);
    }
    if (w.size() >= 3) faces.push_back({std::move(w), i});
  }
  if (faces.size() < 4) {
    ++stats.empty_brushes;
    return false;
  }
  for (const auto& f : faces)
    for (const Vec3& p : f.winding)
      if (std::abs(p.x) > kBaseWinding / 2 || std::abs(p.y) > kBaseWinding / 2 ||
          std::abs(p.z) > kBaseWinding / 2) {
        ++stats.open_brushes;
        return false;
      }
  // Weld corners: each corner becomes the first corner seen within kBrushWeld of it.
  std::vector<Vec3> corners;
  for (auto& f : faces) {
    std::vector<Vec3> welded;
    for (const Vec3& p : f.winding) {
      const Vec3* match = nullptr;
      for (const Vec3& c : corners)
        if (glm::distance(c, p) <= kBrushWeld) {
          match = &c;
          break;
        }
      if (match && glm::distance(*match, p) > 0.0) ++stats.welded_corners;
      if (!match) {
        corners.push_back(p);
        match = &corners.back();
      }
      const Vec3 q = *match;
      if (welded.empty() || welded.back() != q) welded.push_back(q);
    }
    while (welded.size() > 1 && welded.back() == welded.front()) welded.pop_back();
    if (welded.size() < 3) {
      ++stats.sliver_faces;
      continue;
    }
    f.winding = std::move(welded);
    for (const Vec3& p : f.winding) out.bounds.add(p);
    out.faces.push_back(std::move(f));
  }
  if (out.faces.size() < 4) {
    ++stats.empty_brushes;
    return false;
  }
  return true;
}

}  // namespace walk::compiler
