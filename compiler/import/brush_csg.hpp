#pragma once
// The CSG step of a BSP compiler: removes the parts of brush faces that lie inside other brushes. Faces that
// touch a neighbour's face back to back disappear (both are hidden); of two coincident faces facing the same
// way only the earlier brush's stays (later brushes take precedence, as in qbsp).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "compiler/import/brush_geometry.hpp"

namespace walk::compiler {

struct CsgFace {
  std::vector<model::Vec3> winding;
  std::size_t brush = 0;
  std::size_t face = 0;  // index into that brush's faces
};

struct CsgStats {
  std::size_t faces_in = 0;
  std::size_t faces_hidden = 0;  // faces entirely inside other brushes
  std::size_t faces_split = 0;   // faces partly hidden, kept as fragments
  std::size_t fragments_out = 0;
};

// `hides[i]`: brush i hides what is inside it (solid); non-solid brushes (liquids) are clipped but clip none.
// Only brushes [0, output_count) produce faces: the rest only hide (the world around a door entity).
[[nodiscard]] std::vector<CsgFace> csg_faces(const std::vector<ConvexBrush>& brushes,
                                             const std::vector<bool>& hides, CsgStats& stats,
                                             std::size_t output_count = SIZE_MAX);

}  // namespace walk::compiler
