#pragma once
// Conversion between 3D polygons on a plane and Clipper's integer 2D paths in that plane's frame.
#include <map>
#include <polyclipping/clipper.hpp>
#include <utility>
#include <vector>

#include "compiler/geometry/plane_frame.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Clipper units per metre: 1 micrometre resolution, far below modelling precision (EnergyPlus writes 10 um).
// Coordinates are relative to the frame origin (a vertex of the polygon), so a 1 km building spans 1e9
// units, which still keeps Clipper on its fast 64-bit path (it switches to 128-bit products above ~1.07e9).
inline constexpr double kClipperScale = 1e6;

[[nodiscard]] ClipperLib::IntPoint to_int(const glm::dvec2& q);
[[nodiscard]] glm::dvec2 from_int(const ClipperLib::IntPoint& p);

// Signed area of a Clipper path in square metres (positive when counter-clockwise).
[[nodiscard]] double area_m2(const ClipperLib::Path& path);

// `paths` grown by `metres` (shrunk when negative), mitred corners.
[[nodiscard]] ClipperLib::Paths offset_region(const ClipperLib::Paths& paths, double metres);
// The closing of `paths` by `radius` metres (grown, then shrunk back): gaps and notches narrower than twice
// the radius are filled; mitred corners come back no larger.
[[nodiscard]] ClipperLib::Paths close_region(const ClipperLib::Paths& paths, double radius);

// Maps integer points back to 3D. Points registered with `remember` come back exactly as given (so vertices
// that Clipper passes through untouched keep full double precision); others are placed on the plane.
class PointMap {
 public:
  explicit PointMap(const PlaneFrame& frame) : frame_(frame) {}

  // Converts a 3D loop (projected onto the plane) to a path, remembering its exact vertices.
  ClipperLib::Path to_path(const std::vector<model::Vec3>& loop);
  void remember(const ClipperLib::IntPoint& p, const model::Vec3& exact) { exact_.emplace(key(p), exact); }
  [[nodiscard]] model::Vec3 to_3d(const ClipperLib::IntPoint& p) const;
  // Was `p` registered (an exact vertex), rather than placed on the plane from its integer coordinates?
  [[nodiscard]] bool exact(const ClipperLib::IntPoint& p) const { return exact_.count(key(p)) > 0; }
  [[nodiscard]] const PlaneFrame& frame() const { return frame_; }

 private:
  static std::pair<ClipperLib::cInt, ClipperLib::cInt> key(const ClipperLib::IntPoint& p) {
    return {p.X, p.Y};
  }

  PlaneFrame frame_;
  std::map<std::pair<ClipperLib::cInt, ClipperLib::cInt>, model::Vec3> exact_;
};

}  // namespace walk::compiler
