#include "compiler/partition/axial_cover.hpp"

#include <cmath>

namespace walk::compiler {
ClipperLib::IntPoint axial_point(double u, double v) {
  return {static_cast<ClipperLib::cInt>(std::llround(u * kAxialClipperScale)),
          static_cast<ClipperLib::cInt>(std::llround(v * kAxialClipperScale))};
}

ClipperLib::Path rect_path(const Box& box, int axis) {
  const int u = u_axis(axis), v = v_axis(axis);
  return {axial_point(box.min[u], box.min[v]), axial_point(box.max[u], box.min[v]),
          axial_point(box.max[u], box.max[v]), axial_point(box.min[u], box.max[v])};
}

ClipperLib::Paths union_of(const std::vector<std::uint32_t>& ids, const std::vector<VisPolygon>& polygons,
                           int axis, const Box* clip_to) {
  const int u = u_axis(axis), v = v_axis(axis);
  ClipperLib::Clipper c;
  bool any = false;
  for (const auto id : ids) {
    const auto& p = polygons[id];
    if (clip_to) {
      bool off = false;
      for (int a : {u, v})
        if (p.box.max[a] < clip_to->min[a] || p.box.min[a] > clip_to->max[a]) off = true;
      if (off) continue;
    }
    for (const auto& t : p.triangles) {
      ClipperLib::Path path{axial_point(t[0][u], t[0][v]), axial_point(t[1][u], t[1][v]),
                            axial_point(t[2][u], t[2][v])};
      const double a = ClipperLib::Area(path);
      if (a == 0.0) continue;
      // Back-to-back faces (a floor and the ceiling below it) project with opposite windings, which would
      // cancel under the non-zero rule: orient every triangle the same way.
      if (a < 0.0) ClipperLib::ReversePath(path);
      c.AddPath(path, ClipperLib::ptSubject, true);
      any = true;
    }
  }
  ClipperLib::Paths out;
  if (!any) return out;
  c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  if (clip_to) {
    ClipperLib::Clipper k;
    k.AddPaths(out, ClipperLib::ptSubject, true);
    k.AddPath(rect_path(*clip_to, axis), ClipperLib::ptClip, true);
    ClipperLib::Paths clipped;
    k.Execute(ClipperLib::ctIntersection, clipped, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return clipped;
  }
  return out;
}

double area_of(const ClipperLib::Paths& paths) {
  double a = 0.0;
  for (const auto& p : paths) a += ClipperLib::Area(p);  // holes come back with the opposite orientation
  return std::abs(a) / (kAxialClipperScale * kAxialClipperScale);
}

ClipperLib::Paths open_region(const ClipperLib::Paths& paths, double radius) {
  const double r = radius * kAxialClipperScale;
  ClipperLib::Paths shrunk, grown;
  ClipperLib::ClipperOffset in;
  in.AddPaths(paths, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  in.Execute(shrunk, -r);
  if (shrunk.empty()) return {};
  ClipperLib::ClipperOffset out;
  out.AddPaths(shrunk, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  out.Execute(grown, r);
  // Growing back may poke past the original by miter rounding: keep it inside.
  ClipperLib::Clipper c;
  c.AddPaths(grown, ClipperLib::ptSubject, true);
  c.AddPaths(paths, ClipperLib::ptClip, true);
  ClipperLib::Paths result;
  c.Execute(ClipperLib::ctIntersection, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return result;
}

}  // namespace walk::compiler
