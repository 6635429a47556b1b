#pragma once
// Seals modelling slits between coplanar faces. An exporter that writes each zone's surfaces on their own
// leaves thin gaps where two zones' floors (or ceilings, or walls) should meet: EnergyPlus writes faces of
// at most four corners, so a floor whose edge follows a wall that bends is cut straight across, up to
// 14 mm off the wall line in the shared house. Sight lines pass through such slits (a floor seen from
// above shows the room below through a thin line of pixels), and a visibility proof that treats them as
// closed misses those pixels. Here the opaque faces of each plane and facing are united, closed by half the
// given width (grown, then shrunk back), and every slit the closing fills becomes a face of its own, with
// the material of the face nearest to it. Openings wider than the width (doors, windows, stair holes) stay.
#include <cstddef>
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

struct SealStats {
  std::size_t planes = 0;  // plane-and-facing groups of two or more opaque faces
  std::size_t faces_added = 0;
  double area = 0.0;  // square metres sealed
  [[nodiscard]] std::string summary() const;
};

// Slits narrower than `width` (metres) between opaque faces lying in one plane and facing one way are
// filled. Faces within kSealPlaneTolerance of a plane lie in it.
SealStats seal_gaps(model::Model& model, double width);

// EnergyPlus prints 5 decimals (10 um); faces of one floor level or wall plane agree to that.
inline constexpr double kSealPlaneTolerance = 1e-4;

}  // namespace walk::compiler
