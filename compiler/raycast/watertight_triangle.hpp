#pragma once
// Watertight ray/triangle intersection after Woop, Benthin & Wald (JCGT 2013), in double precision.
// The ray is made the z axis of a sheared frame; every vertex is transformed once per ray the same way
// whichever triangle it belongs to, and the 2D edge functions about the ray are evaluated with an exact sign,
// so a ray through a shared edge or vertex meets at least one of the triangles around it (edges inclusive).
#include <cmath>

#include "model/model.hpp"

namespace walk::compiler {

// a*b - c*d with the correct sign (Kahan's difference of products via FMA: error under 2 ulp of the result).
[[nodiscard]] inline double diff_of_products(double a, double b, double c, double d) {
  const double w = c * d;
  const double e = std::fma(-c, d, w);  // exact: w - c*d
  const double f = std::fma(a, b, -w);
  return f + e;
}

// The per-ray part of the test: axis permutation and shear.
struct ShearedRay {
  model::Vec3 origin{0.0};
  int kx = 0, ky = 1, kz = 2;
  double ox = 0.0, oy = 0.0, oz = 0.0;  // origin[kx], origin[ky], origin[kz]
  double sx = 0.0, sy = 0.0, sz = 1.0;
  bool valid = false;  // false for a zero or non-finite direction: such a ray hits nothing

  ShearedRay() = default;  // not valid: a ray set up later
  ShearedRay(const model::Vec3& o, const model::Vec3& d);
};

// Edge functions whose rounded value is smaller than this fraction of their terms' magnitude may have the
// wrong sign (3 roundings of ~1.1e-16 each) and are recomputed with diff_of_products.
inline constexpr double kSignFilter = 4.0e-16;

// The 2D edge function ax*by - ay*bx with an exact sign.
[[nodiscard]] inline double edge_function(double ax, double ay, double bx, double by) {
  const double l = ax * by;
  const double r = ay * bx;
  const double e = l - r;
  if (std::abs(e) > kSignFilter * (std::abs(l) + std::abs(r))) return e;
  return diff_of_products(ax, by, ay, bx);
}

// Hit with tmin < t < tmax: sets t and returns true. Degenerate triangles and rays in the triangle's plane
// never hit. Inline: the BSP's leaves call it for every triangle they hold.
[[nodiscard]] inline bool intersect_watertight(const ShearedRay& r, const model::Vec3& a,
                                               const model::Vec3& b, const model::Vec3& c, double tmin,
                                               double tmax, double& t) {
  // Each vertex coordinate loaded straight from memory by its permuted axis (glm stores x, y, z in a row;
  // its operator[] with a run-time axis is a switch, and a local array indexed at run time waits on a store
  // to the stack).
  const double* pa = &a.x;
  const double* pb = &b.x;
  const double* pc = &c.x;
  const double Az = pa[r.kz] - r.oz, Bz = pb[r.kz] - r.oz, Cz = pc[r.kz] - r.oz;
  const double ax = (pa[r.kx] - r.ox) - r.sx * Az, ay = (pa[r.ky] - r.oy) - r.sy * Az;
  const double bx = (pb[r.kx] - r.ox) - r.sx * Bz, by = (pb[r.ky] - r.oy) - r.sy * Bz;
  const double cx = (pc[r.kx] - r.ox) - r.sx * Cz, cy = (pc[r.ky] - r.oy) - r.sy * Cz;
  const double u = edge_function(cx, cy, bx, by);
  const double v = edge_function(ax, ay, cx, cy);
  const double w = edge_function(bx, by, ax, ay);
  // One branch, not up to six: each sign on its own is a coin toss for a ray that misses.
  if (((u < 0.0) | (v < 0.0) | (w < 0.0)) & ((u > 0.0) | (v > 0.0) | (w > 0.0))) return false;
  const double det = u + v + w;
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double T = (u * Az + v * Bz + w * Cz) * r.sz;
  t = T / det;
  return t > tmin && t < tmax;
}

}  // namespace walk::compiler
