#include "compiler/geometry/clipper_convert.hpp"

#include <cmath>

namespace walk::compiler {

ClipperLib::IntPoint to_int(const glm::dvec2& q) {
  return {static_cast<ClipperLib::cInt>(std::llround(q.x * kClipperScale)),
          static_cast<ClipperLib::cInt>(std::llround(q.y * kClipperScale))};
}

glm::dvec2 from_int(const ClipperLib::IntPoint& p) {
  return {static_cast<double>(p.X) / kClipperScale, static_cast<double>(p.Y) / kClipperScale};
}

double area_m2(const ClipperLib::Path& path) {
  return ClipperLib::Area(path) / (kClipperScale * kClipperScale);
}

ClipperLib::Paths offset_region(const ClipperLib::Paths& paths, double metres) {
  ClipperLib::ClipperOffset o;
  o.AddPaths(paths, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  ClipperLib::Paths out;
  o.Execute(out, metres * kClipperScale);
  return out;
}

ClipperLib::Paths close_region(const ClipperLib::Paths& paths, double radius) {
  if (paths.empty()) return paths;
  return offset_region(offset_region(paths, radius), -radius);
}

ClipperLib::Path PointMap::to_path(const std::vector<model::Vec3>& loop) {
  ClipperLib::Path path;
  path.reserve(loop.size());
  for (const auto& p : loop) {
    const model::Vec3 on_plane = frame_.project(p);
    const ClipperLib::IntPoint q = to_int(frame_.to_2d(on_plane));
    if (!path.empty() && path.back() == q) continue;
    remember(q, on_plane);
    path.push_back(q);
  }
  while (path.size() > 1 && path.back() == path.front()) path.pop_back();
  return path;
}

model::Vec3 PointMap::to_3d(const ClipperLib::IntPoint& p) const {
  const auto it = exact_.find(key(p));
  return it != exact_.end() ? it->second : frame_.to_3d(from_int(p));
}

}  // namespace walk::compiler
