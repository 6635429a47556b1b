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
  // Plain arrays: glm's operator[] with a run-time axis is a switch, three branches per use.
  const double A[3] = {a.x - r.origin.x, a.y - r.origin.y, a.z - r.origin.z};
  const double B[3] = {b.x - r.origin.x, b.y - r.origin.y, b.z - r.origin.z};
  const double C[3] = {c.x - r.origin.x, c.y - r.origin.y, c.z - r.origin.z};
  const double ax = A[r.kx] - r.sx * A[r.kz], ay = A[r.ky] - r.sy * A[r.kz];
  const double bx = B[r.kx] - r.sx * B[r.kz], by = B[r.ky] - r.sy * B[r.kz];
  const double cx = C[r.kx] - r.sx * C[r.kz], cy = C[r.ky] - r.sy * C[r.kz];
  const double u = edge_function(cx, cy, bx, by);
  const double v = edge_function(ax, ay, cx, cy);
  const double w = edge_function(bx, by, ax, ay);
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
  const double det = u + v + w;
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double T = (u * A[r.kz] + v * B[r.kz] + w * C[r.kz]) * r.sz;
  t = T / det;
  return t > tmin && t < tmax;
}

}  // namespace walk::compiler
