#pragma once
// A plane's cover (the united occluders of occluder_planes.hpp) indexed for the hidden-polygon proofs, which
// ask millions of times whether a small convex section lies inside it. A Clipper difference over the whole
// cover per question spent almost all of DM1's proof time adding the cover's paths and opening the result;
// here the cover's boundary segments sit in a uniform grid, and the question is answered with the few
// segments near the section: none crosses the section's inside, and one point of it is covered.
#include <cstdint>
#include <polyclipping/clipper.hpp>
#include <vector>

namespace walk::compiler {

class CoverIndex {
 public:
  CoverIndex() = default;
  // `cover`: Clipper paths, outer loops counter-clockwise and holes clockwise (a union's output).
  explicit CoverIndex(const ClipperLib::Paths& cover);

  // Does the convex, counter-clockwise `section` (Clipper units), shrunk by `inset` units on every side,
  // lie inside the cover? A section thinner than twice the inset counts as inside: no sight of that width
  // passes it.
  [[nodiscard]] bool contains(const ClipperLib::Path& section, double inset) const;
  // The cover's paths whose bounds meet [lo, hi] (Clipper units): within that box they are the whole cover.
  void paths_near(const ClipperLib::IntPoint& lo, const ClipperLib::IntPoint& hi,
                  ClipperLib::Paths& out) const;

 private:
  struct Segment {
    double ax, ay, bx, by;
  };
  struct PathBounds {
    ClipperLib::IntPoint lo, hi;
  };
  [[nodiscard]] int column(double x) const;
  [[nodiscard]] int row(double y) const;
  // Winding number of the cover about (x, y): crossings of the boundary right of it.
  [[nodiscard]] int winding(double x, double y) const;

  ClipperLib::Paths paths_;
  std::vector<PathBounds> path_bounds_;
  std::vector<Segment> segments_;
  std::vector<std::vector<std::uint32_t>> cells_;  // segment ids per grid cell, row-major
  double x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
};

}  // namespace walk::compiler
