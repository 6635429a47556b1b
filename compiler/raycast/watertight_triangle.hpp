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
  model::Vec3 origin;
  int kx = 0, ky = 1, kz = 2;
  double sx = 0.0, sy = 0.0, sz = 1.0;
  bool valid = false;  // false for a zero or non-finite direction: such a ray hits nothing

  ShearedRay(const model::Vec3& o, const model::Vec3& d);
};

// Hit with tmin < t < tmax: sets t and returns true. Degenerate triangles and rays in the triangle's plane
// never hit.
[[nodiscard]] bool intersect_watertight(const ShearedRay& ray, const model::Vec3& a, const model::Vec3& b,
                                        const model::Vec3& c, double tmin, double tmax, double& t);

}  // namespace walk::compiler
