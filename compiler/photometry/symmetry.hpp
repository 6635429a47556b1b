#pragma once
// Photometric files store only the C planes their symmetry needs; this expands them to the full circle that
// model::IntensityDistribution holds.
#include <vector>

#include "model/intensity_distribution.hpp"

namespace walk::compiler {

enum class CSymmetry {
  Rotational,    // one C plane serves every C
  Quadrant,      // planes C0..C90, mirrored into the other three quadrants
  BilateralC0,   // planes C0..C180, mirrored about the C0-C180 plane
  BilateralC90,  // planes C90..C270, mirrored about the C90-C270 plane
  None,          // planes over the whole circle (C360 may be left out: it is C0)
};

// Fills d.c_deg and d.candela from the stored planes (`rows`: one per stored angle, gamma values each).
// Throws walk::Error naming d.source when the stored angles do not fit the symmetry.
void expand_symmetry(model::IntensityDistribution& d, CSymmetry symmetry, const std::vector<double>& stored_c,
                     const std::vector<std::vector<double>>& rows);

}  // namespace walk::compiler
