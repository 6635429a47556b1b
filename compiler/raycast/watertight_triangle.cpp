#include "compiler/raycast/watertight_triangle.hpp"

#include <utility>

namespace walk::compiler {
namespace {

// Edge functions whose rounded value is smaller than this fraction of their terms' magnitude may have the
// wrong sign (3 roundings of ~1.1e-16 each) and are recomputed with diff_of_products.
constexpr double kSignFilter = 4.0e-16;

double edge(double ax, double ay, double bx, double by) {
  const double l = ax * by;
  const double r = ay * bx;
  const double e = l - r;
  if (std::abs(e) > kSignFilter * (std::abs(l) + std::abs(r))) return e;
  return diff_of_products(ax, by, ay, bx);
}

}  // namespace

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
  valid = true;
}

bool intersect_watertight(const ShearedRay& r, const model::Vec3& a, const model::Vec3& b,
                          const model::Vec3& c, double tmin, double tmax, double& t) {
  const model::Vec3 A = a - r.origin;
  const model::Vec3 B = b - r.origin;
  const model::Vec3 C = c - r.origin;
  const double ax = A[r.kx] - r.sx * A[r.kz], ay = A[r.ky] - r.sy * A[r.kz];
  const double bx = B[r.kx] - r.sx * B[r.kz], by = B[r.ky] - r.sy * B[r.kz];
  const double cx = C[r.kx] - r.sx * C[r.kz], cy = C[r.ky] - r.sy * C[r.kz];
  const double u = edge(cx, cy, bx, by);
  const double v = edge(ax, ay, cx, cy);
  const double w = edge(bx, by, ax, ay);
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
  const double det = u + v + w;
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double T = (u * A[r.kz] + v * B[r.kz] + w * C[r.kz]) * r.sz;
  t = T / det;
  return t > tmin && t < tmax;
}

}  // namespace walk::compiler
