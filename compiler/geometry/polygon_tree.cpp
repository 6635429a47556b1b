#include "compiler/geometry/polygon_tree.hpp"

namespace walk::compiler {
namespace {

std::vector<model::Vec3> loop_3d(ClipperLib::Path path, const PointMap& points, bool counter_clockwise) {
  if (ClipperLib::Orientation(path) != counter_clockwise) ClipperLib::ReversePath(path);
  std::vector<model::Vec3> loop;
  loop.reserve(path.size());
  for (const auto& p : path) loop.push_back(points.to_3d(p));
  return loop;
}

void collect(const ClipperLib::PolyNode& outer, const PointMap& points, std::vector<PolygonWithHoles>& out) {
  if (outer.Contour.size() < 3) return;
  PolygonWithHoles polygon;
  polygon.vertices = loop_3d(outer.Contour, points, true);
  for (const ClipperLib::PolyNode* hole : outer.Childs) {
    if (hole->Contour.size() >= 3) polygon.holes.push_back(loop_3d(hole->Contour, points, false));
    for (const ClipperLib::PolyNode* island : hole->Childs) collect(*island, points, out);
  }
  out.push_back(std::move(polygon));
}

}  // namespace

std::vector<PolygonWithHoles> polygons_from_tree(const ClipperLib::PolyTree& tree, const PointMap& points) {
  std::vector<PolygonWithHoles> out;
  for (const ClipperLib::PolyNode* outer : tree.Childs) collect(*outer, points, out);
  return out;
}

}  // namespace walk::compiler
