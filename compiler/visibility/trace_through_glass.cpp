#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {

void trace_through_glass(const RayCaster& caster, Ray ray, const std::vector<char>& glass,
                         std::vector<std::uint32_t>& ids) {
  for (int layer = 0; layer <= kMaxGlassLayers; ++layer) {
    const RayHit h = caster.closest(ray);
    if (!h.hit()) return;
    ids.push_back(h.polygon);
    if (h.polygon >= glass.size() || !glass[h.polygon]) return;
    ray.tmin = h.t + self_hit_tmin(ray.dir);
  }
}

}  // namespace walk::compiler
