#pragma once
// Geometry clean-up between import and the rest of the compiler, so that later stages see stable numerics:
// vertices within a tolerance relative to the model's size are welded, repeated and collinear corners are
// removed, zero-area faces are dropped, a face repeating another's welded corners on the same side is
// dropped (it would z-fight and split the light between two copies), non-planar faces are split into
// planar triangles, and overlapping
// coplanar faces are detected (and reported, not removed: EnergyPlus windows and doors are coplanar with
// their walls on purpose and the openings stage cuts them). Concave faces with holes are kept whole: the
// mesher triangulates them exactly. Recentring far-away models is the pipeline's "recentre" stage.
#include <cstddef>
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

// Weld distance as a fraction of the model's bounding-box diagonal: 1e-7 welds corners within 10 um in a
// 100 m building and within 0.2 um in the 2 m Cornell box; far below any real feature, far above double
// round-off at 1e6 m (1e-10 m). A file printed more coarsely than that needs the scene's `[model] weld`:
// EnergyPlus prints 10 um steps, so one wall's corner can sit 10 um from its neighbour's and leave a crack
// that sight lines pass through (the house's full-size PVS check saw one pixel through one). 1e-6 would
// close those everywhere but drops a quarter of the finely tessellated conference room's faces.
inline constexpr double kWeldRelative = 1e-7;
// A face is non-planar when a corner lies further than this fraction of its size (largest bounding-box
// side) off its best plane: 1e-3 is 1 mm on a 1 m quad; the Cornell box's red wall (3.2 mm on 0.55 m) is
// above it and is split, EnergyPlus faces (5 decimals) are below it.
inline constexpr double kNonPlanarRelative = 1e-3;
// Coplanar-overlap detection skips planes holding more faces than this (a triangulated floor of thousands
// of triangles would cost millions of polygon intersections); the report says how many were skipped.
inline constexpr std::size_t kMaxFacesPerPlaneCheck = 2000;

struct CleanupStats {
  double weld_tolerance = 0.0;         // metres, as used
  std::size_t vertices_welded = 0;     // corners moved onto a nearby one
  std::size_t corners_removed = 0;     // repeated or collinear corners taken out of faces
  std::size_t faces_dropped = 0;       // zero-area (or collinear) faces removed
  std::size_t nonplanar_split = 0;     // non-planar faces replaced by triangles
  std::size_t triangles_added = 0;     // triangles those became
  std::size_t duplicates_dropped = 0;  // faces repeating another's corners exactly on the same side
  std::uint32_t first_duplicate_line = 0, first_duplicated_line = 0;  // source lines of the first pair
  std::size_t coplanar_overlaps = 0;  // pairs of same-facing coplanar faces that overlap in area
  std::size_t planes_unchecked = 0;   // planes with too many faces to check for overlaps
  [[nodiscard]] std::string summary() const;
};

// `weld_metres`: the scene's weld distance in metres, or 0 for kWeldRelative of the diagonal.
CleanupStats clean_up(model::Model& model, double weld_metres = 0.0);

}  // namespace walk::compiler
