#pragma once
// How photometric quantities map onto the solver's radiant RGB watts. The solver and the display work per
// RGB channel in W and W/m2 of linear Rec. 709 (sRGB) light; one lumen is 1/179 W of equal-energy white, the
// luminous efficacy Radiance uses (WHTEFFICACY), so a scene's lux agree with a Radiance model of it.
#include "model/model.hpp"

namespace walk::model {

inline constexpr double kLumensPerWatt = 179.0;

// Luminance weight of a linear Rec. 709 colour: the Y row of its XYZ matrix.
[[nodiscard]] inline double luminance_weight(const Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Radiant power per channel (W) of a luminaire emitting `lumens` in colour `colour` (any scale, not black).
[[nodiscard]] inline Rgb power_from_lumens(double lumens, const Rgb& colour) {
  return colour * (lumens / (kLumensPerWatt * luminance_weight(colour)));
}

// Illuminance (lux) of an irradiance per channel (W/m2); luminance (cd/m2) of a diffuse surface's radiosity
// is this divided by pi.
[[nodiscard]] inline double lux_from_irradiance(const Rgb& e) {
  return kLumensPerWatt * luminance_weight(e);
}

}  // namespace walk::model
