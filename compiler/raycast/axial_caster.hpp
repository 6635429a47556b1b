#pragma once
// The paper's ray caster: axial polygons in sorted planes (AxialPlanes), the rest in a BSP tree (PolygonBsp)
// searched only up to the axial hit, only over the blocks holding its triangles that the walk passed
// (closest hits: only where it passed the bounds of their parts in the block; none: no BSP search at all),
// and from the node that encloses those parts rather than the root. When the BSP holds most of the model
// (a sculpted, non-axial mesh) the order turns round: the BSP first, and the plane walk stops at its hit.
#include "compiler/raycast/axial_planes.hpp"
#include "compiler/raycast/polygon_bsp.hpp"

namespace walk::compiler {

class AxialCaster final : public RayCaster {
 public:
  explicit AxialCaster(std::span<const Triangle> triangles, const BlockSizing& sizing = {});
  [[nodiscard]] std::string_view name() const override { return "axial"; }
  [[nodiscard]] RayHit closest(const Ray& ray) const override;
  [[nodiscard]] bool occluded(const Ray& ray) const override;
  [[nodiscard]] std::size_t memory_bytes() const override;

  [[nodiscard]] const AxialPlanes& planes() const { return planes_; }
  [[nodiscard]] const PolygonBsp& bsp() const { return bsp_; }

 private:
  LocalTriangles local_;
  std::vector<std::uint8_t> axial_;  // per triangle: taken by the planes (build scratch, then freed)
  AxialPlanes planes_;
  PolygonBsp bsp_;
  bool bsp_first_ = false;
  bool bsp_marked_ = false;  // the planes' blocks are marked where the BSP's triangles are
  // The BSP node to search from after a walk that passed `span`: the common ancestor of the nodes enclosing
  // the marked boxes passed (the root when there were too many to list); kNoHit for no search at all.
  [[nodiscard]] std::uint32_t bsp_start(const MarkedSpan& span) const;
};

}  // namespace walk::compiler
