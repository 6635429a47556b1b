#pragma once
// The paper's structure for axial polygons (Airey, Rohlf & Brooks 1990): triangles lying in a plane x = c,
// y = c or z = c are grouped by plane, the planes of each axis are sorted by c, and a ray walks the three
// sorted lists in merged order of ray parameter, testing only the polygons of each plane it reaches. The walk
// runs block by block (PlaneBlocks): each block of a uniform 3D grid lists only the planes with polygons
// inside it, so a ray skips the planes of rooms off to the side, and a plane's listing in a block holds only
// its polygons there, so a plane with thousands of polygons costs one lookup (the blocks' cells are the
// plane's 2D grid) and a few 2D tests.
//
// The 2D test is conservative by kEdgeSlack: a point within that distance outside a polygon's edge counts as
// inside. The hit point in a plane is rounded (about 1e-13 m in a 1 km building), so without slack a ray
// aimed at the edge where two planes meet (a room's corner) could round to the outside of both walls and
// leak; with it, it hits both and the tie rule picks one. Rays through shared edges inside one plane see the
// same rounded point for both polygons and are covered likewise.
#include <cstdint>
#include <vector>

#include "compiler/raycast/local_triangles.hpp"
#include "compiler/raycast/plane_blocks.hpp"

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
    std::size_t cell_entries = 0;  // element copies in all block listings
  };

  // Takes the triangles whose three vertices share one coordinate exactly and marks them in `taken`; about
  // blocks sized by `sizing` (per element: a triangle or merged rectangle).
  AxialPlanes(const LocalTriangles& triangles, std::vector<std::uint8_t>& taken,
              const BlockSizing& sizing = {});

  // Improves `best` with the closest axial hit in (tmin, min(tmax, best.t + tie)); origin is local.
  // `marked` (may be null): see PlaneBlocks::walk.
  void closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax, double tie,
               RayHit& best, MarkedSpan* marked = nullptr) const;
  [[nodiscard]] bool occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                              MarkedSpan* marked = nullptr) const;
  // Marks the blocks the triangle reaches (PlaneBlocks::mark).
  bool mark(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c) {
    return blocks_.mark(a, b, c);
  }
  template <class F>
  void tag_marks(F&& f) {
    blocks_.tag_marks(f);
  }

  [[nodiscard]] const Stats& stats() const { return stats_; }
  [[nodiscard]] const PlaneBlocks& blocks() const { return blocks_; }
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
  template <bool kAny>
  bool walk(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax, double tie,
            RayHit* best, MarkedSpan* marked) const;

  std::vector<EdgeLine> edges_;
  // Elements copied in place per block listing (PlaneBlocks::items order): a crossing reads one contiguous
  // run, with no index to chase.
  std::vector<Element> cell_elements_;
  Stats stats_;
  PlaneBlocks blocks_;
};

}  // namespace walk::compiler
