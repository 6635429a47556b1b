#include "compiler/raycast/brute_force_caster.hpp"

#include <algorithm>

#include "compiler/raycast/watertight_triangle.hpp"

namespace walk::compiler {

RayHit BruteForceCaster::closest(const Ray& ray) const {
  RayHit best;
  const ShearedRay r(ray.origin - local_.centre, ray.dir);
  if (!r.valid) return best;
  const double tie = tie_tolerance(ray.dir);
  const auto& tris = local_.triangles;
  for (std::uint32_t i = 0; i < tris.size(); ++i) {
    double t = 0.0;
    const double limit = best.hit() ? std::min(ray.tmax, best.t + tie) : ray.tmax;
    if (!intersect_watertight(r, tris[i].a, tris[i].b, tris[i].c, std::max(ray.tmin, 0.0), limit, t))
      continue;
    const bool front = local_.front(i, ray.dir);
    if (better_hit(t, front, i, best, tie)) best = {t, i, tris[i].polygon, front};
  }
  return best;
}

bool BruteForceCaster::occluded(const Ray& ray) const {
  const ShearedRay r(ray.origin - local_.centre, ray.dir);
  if (!r.valid) return false;
  for (const auto& tri : local_.triangles) {
    double t = 0.0;
    if (intersect_watertight(r, tri.a, tri.b, tri.c, std::max(ray.tmin, 0.0), ray.tmax, t)) return true;
  }
  return false;
}

}  // namespace walk::compiler
