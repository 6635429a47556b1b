#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {

RayHit trace_through_glass(const RayCaster& caster, Ray ray, const std::vector<char>& glass,
                           std::vector<std::uint32_t>& ids, bool cull_back_faces) {
  RayHit last;
  for (int layer = 0; layer <= kMaxGlassLayers; ++layer) {
    const RayHit h = caster.closest(ray);
    if (!h.hit()) return RayHit{};
    last = h;
    const bool see_through = h.polygon < glass.size() && glass[h.polygon];
    if (!cull_back_faces || h.front || see_through) {  // else not drawn: what lies behind shows
      ids.push_back(h.polygon);
      if (!see_through) return h;
    }
    // On from just past this hit: the tie distance, not the self-hit distance. The ray's origin has not
    // moved, so its t values carry no origin rounding; a wall's back-to-back copy a rounding apart (38 nm in
    // the house's slanted walls) lies well inside the 1 um self-hit distance and would be skipped with it,
    // letting the sight line through a wall the renderer draws.
    ray.tmin = h.t + tie_tolerance(ray.dir);
  }
  return last;
}

}  // namespace walk::compiler
