#pragma once
// A BSP tree over the polygons that are not axial, as the paper keeps them: each node splits space by the
// plane of one of its polygons or an axis plane (chosen among a sample by the surface-area cost, which
// weighs balance, straddlers and empty space); polygons go to the side they lie on (polygons in the plane to
// the side they face), straddlers to both (referenced, not clipped, so no new slivers); polygons live in the
// leaves. Each node also keeps the bounds of what lies below it, so a ray skips empty space. Searched front
// to back, the search stops once it is beyond the best hit so far (the axial hit).
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/raycast/local_triangles.hpp"
#include "compiler/raycast/watertight_triangle.hpp"

namespace walk::compiler {

class PolygonBsp {
 public:
  struct Stats {
    std::size_t triangles = 0;
    std::size_t nodes = 0;
    std::size_t references = 0;   // triangle references in all nodes (straddlers count more than once)
    std::size_t axis_splits = 0;  // nodes split by an axis plane
    int depth = 0;
  };

  // `triangles` must outlive the tree; `ids` are the triangles it holds.
  PolygonBsp(const LocalTriangles& triangles, std::vector<std::uint32_t> ids);

  // Improves `best` with hits in (tmin, min(tmax, best.t + tie)); the ray (origin, dir) is local. The
  // triangle test's per-ray set-up is done only once the ray meets the tree's bounds. `start` (a node, the
  // root by default) searches only its subtree: enough when the caller knows that the ray can meet the tree's
  // triangles, within the interval, only inside the regions of nodes below it (see enclosing()).
  void closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax, double tie,
               RayHit& best, std::uint32_t start = 0) const;
  [[nodiscard]] bool occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                              std::uint32_t start = 0) const;

  // The deepest node whose region (the side of each split above it that it lies on) holds the whole box
  // [lo, hi] with room for the classification tolerance: a ray segment inside the box can meet only that
  // node's triangles. kNoHit only for an empty tree (an inner node has both children).
  [[nodiscard]] std::uint32_t enclosing(const model::Vec3& lo, const model::Vec3& hi) const;
  // The deepest node with all of `nodes` in its subtree (their lowest common ancestor); kNoHit entries
  // (regions holding no triangle) are left out, and none at all gives kNoHit.
  [[nodiscard]] std::uint32_t common_ancestor(std::span<const std::uint32_t> nodes) const;

  [[nodiscard]] bool empty() const { return nodes_.empty(); }
  [[nodiscard]] const Stats& stats() const { return stats_; }
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  struct Node {
    model::Vec3 normal{0.0};  // unit; the front side is where it points
    double offset = 0.0;      // plane: dot(normal, p) == offset
    model::Vec3 lo{0.0}, hi{0.0};
    std::uint32_t front = kNoHit, back = kNoHit;  // children (kNoHit: none)
    std::uint32_t first = 0, count = 0;           // triangles kept here, in items_
    std::int32_t axis = -1;  // the split plane is axis = offset (normal a unit axis): no dot products
    std::uint32_t parent = kNoHit;
    std::int32_t depth = 0;  // below the root
  };

  std::uint32_t build(std::vector<std::uint32_t>& ids, int depth);
  template <bool kAny>
  bool search(std::uint32_t start, const model::Vec3& origin, const model::Vec3& dir, double tmin,
              double tmax, double tie, RayHit* best) const;

  const LocalTriangles* tris_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> items_;
  Stats stats_;
};

}  // namespace walk::compiler
