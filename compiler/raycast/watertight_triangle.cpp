#include "compiler/raycast/watertight_triangle.hpp"

#include <utility>

namespace walk::compiler {

ShearedRay::ShearedRay(const model::Vec3& o, const model::Vec3& d) : origin(o) {
  const model::Vec3 ad(std::abs(d.x), std::abs(d.y), std::abs(d.z));
  if (!(std::isfinite(ad.x) && std::isfinite(ad.y) && std::isfinite(ad.z) && std::isfinite(o.x) &&
        std::isfinite(o.y) && std::isfinite(o.z)))
    return;
  kz = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
  if (ad[kz] == 0.0) return;
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  if (d[kz] < 0.0) std::swap(kx, ky);  // keep the winding of the frame
  sx = d[kx] / d[kz];
  sy = d[ky] / d[kz];
  sz = 1.0 / d[kz];
  ox = o[kx];
  oy = o[ky];
  oz = o[kz];
  valid = true;
}

}  // namespace walk::compiler
