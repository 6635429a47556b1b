#pragma once
// The colour of a lamp given as a correlated colour temperature.
#include "model/model.hpp"

namespace walk::compiler {

inline constexpr double kMinCct = 1667.0;  // kelvin: the range Kang et al. fit the Planckian locus over
inline constexpr double kMaxCct = 25000.0;

// Linear Rec. 709 colour of a black body at `kelvin` (kMinCct..kMaxCct), scaled to unit luminance. The
// chromaticity is Kang et al. 2002's cubic fit of the Planckian locus (within 1e-3 in xy); a component
// outside the Rec. 709 gamut is clipped to 0.
[[nodiscard]] model::Rgb cct_colour(double kelvin);

}  // namespace walk::compiler
