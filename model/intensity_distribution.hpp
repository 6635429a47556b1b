#pragma once
// A luminaire's luminous intensity distribution in the C-gamma system of IES LM-63 type C and EULUMDAT:
// gamma is the angle from the luminaire's aim (0: straight down for a ceiling downlight), C the angle about
// the aim, counter-clockwise seen from behind the luminaire, from its C0 axis. Candela are absolute (the
// readers fold in lamp flux, multipliers and ballast factor); the grid is expanded from the file's symmetry
// to either one C plane (rotationally symmetric) or C planes covering [0, 360].
#include <cstdint>
#include <string>
#include <vector>

namespace walk::model {

struct IntensityDistribution {
  std::string source;             // "file.ies", for messages
  std::vector<double> gamma_deg;  // strictly increasing, within [0, 180]
  std::vector<double> c_deg;      // strictly increasing; {0} alone, or from 0 to 360
  std::vector<double> candela;    // c_deg.size() rows of gamma_deg.size(): [c][gamma]
  double declared_lumens = 0.0;   // the file's own luminaire (or lamp) flux, 0 when not given
  double lumens = 0.0;            // flux(), kept by finish(): gathering divides by it per receiver

  // Candela towards (gamma, c) in degrees: bilinear in the table, 0 beyond its last gamma, periodic in C.
  [[nodiscard]] double candela_at(double gamma, double c) const;
  // Luminous flux, lm: the intensity integrated over the sphere (midpoint rule, fine enough that the
  // quadrature error is below 1e-4 of the flux for tables at 1 degree or coarser).
  [[nodiscard]] double flux() const;
  [[nodiscard]] std::uint64_t hash() const;
};

// Checks the invariants above and keeps the flux; throws walk::Error naming `source` and what is wrong.
void finish(IntensityDistribution& d);

}  // namespace walk::model
