#include "compiler/raycast/axial_caster.hpp"

#include <glm/common.hpp>

namespace walk::compiler {
namespace {

std::vector<std::uint32_t> not_taken(const std::vector<std::uint8_t>& taken) {
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < taken.size(); ++i)
    if (!taken[i]) ids.push_back(i);
  return ids;
}

}  // namespace

AxialCaster::AxialCaster(std::span<const Triangle> triangles, const BlockSizing& sizing)
    : local_(triangles),
      axial_(local_.triangles.size(), 0),
      planes_(local_, axial_, sizing),
      bsp_(local_, not_taken(axial_)) {
  bsp_first_ = bsp_.stats().triangles > planes_.stats().triangles;
  // The blocks the BSP's triangles reach: a ray whose plane walk passes none of them skips the BSP.
  bsp_marked_ = !bsp_first_ && !bsp_.empty();
  for (const std::uint32_t i : not_taken(axial_)) {
    if (!bsp_marked_) break;
    const Triangle& t = local_.triangles[i];
    bsp_marked_ = planes_.mark(t.a, t.b, t.c);
  }
  // Each marked block's tag: the BSP node enclosing its marked box, where a search through it can start.
  if (bsp_marked_)
    planes_.tag_marks([&](const model::Vec3& lo, const model::Vec3& hi) { return bsp_.enclosing(lo, hi); });
  std::vector<std::uint8_t>().swap(axial_);
  if (bsp_.empty()) {  // only the BSP reads the triangles after the build
    std::vector<Triangle>().swap(local_.triangles);
    std::vector<model::Vec3>().swap(local_.normals);
  }
}

std::uint32_t AxialCaster::bsp_start(const MarkedSpan& span) const {
  if (span.empty()) return kNoHit;
  // The ray meets BSP triangles only inside the marked boxes it passed, each inside its tag's region.
  return span.all_tags() ? bsp_.common_ancestor({span.tags, static_cast<std::size_t>(span.tag_count)}) : 0;
}

RayHit AxialCaster::closest(const Ray& ray) const {
  if (!valid_ray(ray)) return {};
  RayHit best;
  const model::Vec3 o = ray.origin - local_.centre;
  const double tmin = std::max(ray.tmin, 0.0);
  const double tie = tie_tolerance(ray.dir);
  if (bsp_first_) {
    if (!bsp_.empty()) bsp_.closest(o, ray.dir, tmin, ray.tmax, tie, best);
    planes_.closest(o, ray.dir, tmin, ray.tmax, tie, best);
  } else if (bsp_marked_) {
    // The BSP only over the span of blocks holding its triangles that the walk passed before its hit.
    MarkedSpan span;
    planes_.closest(o, ray.dir, tmin, ray.tmax, tie, best, &span);
    const std::uint32_t start = bsp_start(span);
    if (start != kNoHit)
      bsp_.closest(o, ray.dir, std::max(tmin, span.first), std::min(ray.tmax, span.last), tie, best, start);
  } else {
    planes_.closest(o, ray.dir, tmin, ray.tmax, tie, best);
    if (!bsp_.empty()) bsp_.closest(o, ray.dir, tmin, ray.tmax, tie, best);
  }
  return best;
}

bool AxialCaster::occluded(const Ray& ray) const {
  if (!valid_ray(ray)) return false;
  const model::Vec3 o = ray.origin - local_.centre;
  const double tmin = std::max(ray.tmin, 0.0);
  const auto in_bsp = [&] { return !bsp_.empty() && bsp_.occluded(o, ray.dir, tmin, ray.tmax); };
  if (bsp_first_) return in_bsp() || planes_.occluded(o, ray.dir, tmin, ray.tmax);
  if (bsp_marked_) {
    MarkedSpan span;
    if (planes_.occluded(o, ray.dir, tmin, ray.tmax, &span)) return true;
    const std::uint32_t start = bsp_start(span);
    return start != kNoHit &&
           bsp_.occluded(o, ray.dir, std::max(tmin, span.first), std::min(ray.tmax, span.last), start);
  }
  return planes_.occluded(o, ray.dir, tmin, ray.tmax) || in_bsp();
}

std::size_t AxialCaster::memory_bytes() const {
  return local_.memory_bytes() + planes_.memory_bytes() + bsp_.memory_bytes();
}

}  // namespace walk::compiler
