#pragma once
// The paper's structure for axial polygons (Airey, Rohlf & Brooks 1990): triangles lying in a plane x = c,
// y = c or z = c are grouped by plane, the planes of each axis are sorted by c, and a ray walks the three
// sorted lists in merged order of ray parameter, testing only the polygons of each plane it reaches. Inside a
// plane a uniform 2D grid over the plane's polygons turns "which of these thousands contain the point" into
// one cell lookup and a few 2D tests.
//
// The 2D test is conservative by kEdgeSlack: a point within that distance outside a polygon's edge counts as
// inside. The hit point in a plane is rounded (about 1e-13 m in a 1 km building), so without slack a ray
// aimed at the edge where two planes meet (a room's corner) could round to the outside of both walls and
// leak; with it, it hits both and the tie rule picks one. Rays through shared edges inside one plane see the
// same rounded point for both polygons and are covered likewise.
#include <cstdint>
#include <vector>

#include "compiler/raycast/local_triangles.hpp"

namespace walk::compiler {

// How far outside its edges a polygon still counts as hit (1 nm: 1e4 times the rounding of a hit point in a
// 1 km building, a millionth of a millimetre on a wall).
inline constexpr double kEdgeSlack = 1e-9;

class AxialPlanes {
 public:
  struct Stats {
    std::size_t triangles = 0;   // axial triangles taken
    std::size_t elements = 0;    // 2D elements after merging triangle pairs into rectangles
    std::size_t rectangles = 0;  // of which merged rectangles (no edge tests at all)
    std::size_t planes[3] = {0, 0, 0};
    std::size_t planes_left = 0;  // small planes whose triangles were left to the BSP
    std::size_t cells = 0;
    std::size_t cell_entries = 0;  // element copies in all cells
  };

  // Takes the triangles whose three vertices share one coordinate exactly, in planes big enough to be worth a
  // step of the walk; marks them in `taken`.
  AxialPlanes(const LocalTriangles& triangles, std::vector<std::uint8_t>& taken);

  // Improves `best` with the closest axial hit in (tmin, min(tmax, best.t + tie)); origin is local.
  void closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax, double tie,
               RayHit& best) const;
  [[nodiscard]] bool occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin,
                              double tmax) const;

  [[nodiscard]] const Stats& stats() const { return stats_; }
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  struct Element {          // one axial triangle, or two merged into a rectangle, in its plane's (u, v) frame
    double u0, u1, v0, v1;  // bounds widened by kEdgeSlack
    std::uint32_t edge_first;  // into edges_
    std::uint16_t edge_count;  // edges not parallel to u or v (those coincide with the bounds)
    std::int16_t normal_sign;  // sign of the triangle's normal along the plane's axis
    std::uint32_t triangle;
    std::uint32_t polygon;
  };
  struct EdgeLine {  // inside when nu*u + nv*v + c >= 0; (nu, nv) unit length, c widened by kEdgeSlack
    double nu, nv, c;
  };
  struct PlaneBounds {  // what every step of the walk reads, in one 40-byte record
    double coord;
    double u0, u1, v0, v1;  // bounds of its elements
  };
  struct PlaneGrid {           // read only when the point falls inside the bounds
    double inv_du, inv_dv;     // cells per metre
    std::uint32_t nu, nv;      // grid size
    std::uint32_t cell_first;  // into cell_start_: nu*nv + 1 entries
  };

  template <bool kAny>
  bool walk(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax, double tie,
            RayHit* best) const;

  std::vector<double> coords_[3];  // sorted plane coordinates per axis, for the binary search
  std::vector<PlaneBounds> bounds_[3];
  std::vector<PlaneGrid> grids_[3];
  std::vector<EdgeLine> edges_;
  std::vector<std::uint32_t> cell_start_;
  // Each cell's elements copied in place: a lookup reads one contiguous run, with no index to chase (the
  // walk is bound by memory latency on big buildings).
  std::vector<Element> cell_elements_;
  Stats stats_;
};

}  // namespace walk::compiler
