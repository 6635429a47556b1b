#pragma once
// Cuts doors, open passages and windows out of the walls they lie on. In EnergyPlus DXF files these are
// separate faces coplanar with (and inside) their host wall; after cutting, an opening is a hole in the wall
// (and its face is dropped), a window is a hole filled by its own glass polygon.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

// Distance within which a face counts as lying on a wall's plane, metres: EnergyPlus writes 5 decimals and
// windows sit on their wall; 2 mm is well above round-off and below any real wall thickness.
inline constexpr double kCoplanarTolerance = 0.002;

// How far behind (or in front of) a parallel wall a window may sit and still be cut out of it, metres.
// Some exporters (DesignBuilder via EnergyPlus, e.g. the shared house.dxf) place windows 0.13 m inside the
// wall plane, where the real glazing sits in the wall's thickness; 0.3 m covers thick masonry walls and is
// well below the size of any room, so the glass cannot reach a wall on the far side of a room.
inline constexpr double kGlassInsetDepth = 0.3;

struct OpeningStats {
  std::size_t hosts_cut = 0;     // walls that got at least one hole or notch
  std::size_t openings_cut = 0;  // Role::Opening faces used (and removed)
  std::size_t glass_cut = 0;     // Role::Glass faces cut out of a host (and kept)
  std::size_t unmatched = 0;     // opening/glass faces with no coplanar host (kept as they are)
  std::size_t glass_inset = 0;   // of glass_cut: recessed behind their host's plane, cut from its projection
  // Groups (Model::groups) of the opening and glass faces cut out of a host, sorted: a door's or window's
  // frame (jambs, lintel, sill, reveals) lines a hole in the shell, so the cells stage takes it as shell.
  std::vector<std::uint32_t> frame_groups;
};

OpeningStats cut_openings(model::Model& model, double tolerance = kCoplanarTolerance);

}  // namespace walk::compiler
