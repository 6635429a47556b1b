#pragma once
// Clipper's PolyTree (outer contours, their holes, islands inside holes) back to 3D polygons with holes.
#include <polyclipping/clipper.hpp>
#include <vector>

#include "compiler/geometry/clipper_convert.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct PolygonWithHoles {
  std::vector<model::Vec3> vertices;            // counter-clockwise about the frame normal
  std::vector<std::vector<model::Vec3>> holes;  // clockwise
};

// One entry per outer contour (islands inside holes become entries of their own).
[[nodiscard]] std::vector<PolygonWithHoles> polygons_from_tree(const ClipperLib::PolyTree& tree,
                                                               const PointMap& points);

}  // namespace walk::compiler
