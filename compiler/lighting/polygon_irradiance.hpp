#pragma once
// The exact projected solid angle of a convex planar polygon seen from a point: Lambert's formula, as Baum,
// Rushmeier & Winget (1989) use it for form factors. It is the integral of cos(receiver) cos(emitter) / r^2
// over the polygon's area, so a Lambertian emitter of radiance L gives an unshadowed irradiance of L times
// it. Direct light takes a panel's unshadowed light from it and casts shadow rays only for the fraction
// that is shadowed: a receiver that sees the whole panel gets the exact value at any sample count, where
// point samples of cos cos / r^2 are noisy next to the panel.
#include <span>

#include "model/model.hpp"

namespace walk::compiler {

// `polygon`: convex and planar, either winding; `normal`: the receiver's unit normal. Only the part of the
// polygon in front of the receiver's tangent plane counts (a receiver sees its hemisphere). Between 0 and
// pi; 0 when nothing is left, or when the point lies in the polygon's plane.
[[nodiscard]] double projected_solid_angle(std::span<const model::Vec3> polygon, const model::Vec3& point,
                                           const model::Vec3& normal);

}  // namespace walk::compiler
