#include "compiler/photometry/colour_temperature.hpp"

#include <algorithm>

#include "model/photometric_units.hpp"

namespace walk::compiler {

model::Rgb cct_colour(double kelvin) {
  const double t = std::clamp(kelvin, kMinCct, kMaxCct);
  const double t1 = 1e3 / t, t2 = t1 * t1, t3 = t2 * t1;  // in units of 1000 K, so the powers stay small
  const double x = t <= 4000.0 ? -0.2661239 * t3 - 0.2343589 * t2 + 0.8776956 * t1 + 0.179910
                               : -3.0258469 * t3 + 2.1070379 * t2 + 0.2226347 * t1 + 0.240390;
  const double x2 = x * x, x3 = x2 * x;
  const double y = t <= 2222.0   ? -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683
                   : t <= 4000.0 ? -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867
                                 : 3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483;
  // XYZ at Y = 1, then to linear Rec. 709 (IEC 61966-2-1 matrix, D65 white).
  const double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
  model::Rgb rgb{std::max(0.0, 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z),
                 std::max(0.0, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z),
                 std::max(0.0, 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z)};
  return rgb / model::luminance_weight(rgb);
}

}  // namespace walk::compiler
