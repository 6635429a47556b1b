#include "compiler/import/brush_csg.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

using model::Vec3;

// Planes whose normals' dot product is beyond this (in absolute value) and whose distances agree within
// kClipEpsilon are one plane for the coplanar rules: the same angular tolerance as duplicate planes.
constexpr double kCoplanarDot = 1.0 - 1e-10;

bool overlaps(const model::Bounds& a, const model::Bounds& b) {
  for (int k = 0; k < 3; ++k)
    if (a.max[k] < b.min[k] - kClipEpsilon || b.max[k] < a.min[k] - kClipEpsilon) return false;
  return true;
}

// Splits `fragment` against brush `b`: appends the parts outside it to `out`; returns false when some part
// was inside (hidden). `precedence`: `b` comes later, so a same-facing coincident face counts as inside.
bool clip_outside(const std::vector<Vec3>& fragment, const BrushPlane& face_plane, const ConvexBrush& b,
                  bool precedence, std::vector<std::vector<Vec3>>& out) {
  std::vector<Vec3> inside = fragment;
  for (const BrushFace& bf : b.faces) {
    const BrushPlane& p = b.planes[bf.plane];
    const double dot = glm::dot(face_plane.normal, p.normal);
    if (dot > kCoplanarDot && std::abs(face_plane.dist - p.dist) <= kClipEpsilon) {
      if (precedence) continue;  // on the plane, facing the same way: the later brush's face wins
      out.push_back(std::move(inside));
      return true;
    }
    if (dot < -kCoplanarDot && std::abs(face_plane.dist + p.dist) <= kClipEpsilon) continue;  // back to back
    std::vector<Vec3> front;
    inside = clip_winding(inside, p, &front);
    if (front.size() >= 3) out.push_back(std::move(front));
    if (inside.size() < 3) return true;  // wholly outside
  }
  return false;
}

}  // namespace

std::vector<CsgFace> csg_faces(const std::vector<ConvexBrush>& brushes, const std::vector<bool>& hides,
                               CsgStats& stats, std::size_t output_count) {
  std::vector<CsgFace> result;
  for (std::size_t i = 0; i < std::min(brushes.size(), output_count); ++i) {
    const ConvexBrush& a = brushes[i];
    std::vector<std::size_t> near;
    for (std::size_t j = 0; j < brushes.size(); ++j)
      if (j != i && hides[j] && overlaps(a.bounds, brushes[j].bounds)) near.push_back(j);
    for (std::size_t f = 0; f < a.faces.size(); ++f) {
      ++stats.faces_in;
      const BrushPlane& plane = a.planes[a.faces[f].plane];
      std::vector<std::vector<Vec3>> fragments{a.faces[f].winding};
      bool clipped = false;
      for (std::size_t j : near) {
        std::vector<std::vector<Vec3>> next;
        for (const auto& fragment : fragments)
          if (!clip_outside(fragment, plane, brushes[j], j > i, next)) clipped = true;
        fragments = std::move(next);
        if (fragments.empty()) break;
      }
      if (fragments.empty()) {
        ++stats.faces_hidden;
        continue;
      }
      if (clipped) ++stats.faces_split;
      for (auto& w : fragments) {
        result.push_back({std::move(w), i, f});
        ++stats.fragments_out;
      }
    }
  }
  return result;
}

}  // namespace walk::compiler
