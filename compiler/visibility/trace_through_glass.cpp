#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {

RayHit trace_through_glass(const RayCaster& caster, Ray ray, const std::vector<char>& glass,
                           std::vector<std::uint32_t>& ids) {
  RayHit last;
  for (int layer = 0; layer <= kMaxGlassLayers; ++layer) {
    const RayHit h = caster.closest(ray);
    if (!h.hit()) return RayHit{};
    ids.push_back(h.polygon);
    last = h;
    if (h.polygon >= glass.size() || !glass[h.polygon]) return h;
    ray.tmin = h.t + self_hit_tmin(ray.dir);
  }
  return last;
}

}  // namespace walk::compiler
