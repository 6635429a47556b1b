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
    ray.tmin = h.t + self_hit_tmin(ray.dir);
  }
  return last;
}

}  // namespace walk::compiler
