#pragma once
// DXF import. Reads 3DFACE entities (triangles and quads) with their layer, ACI colour and the EnergyPlus
// "ZONE:SURFACE" 999 comment as the face name; layers become model groups. Throws walk::Error naming the file
// and the line of the offending group code for a truncated file, a non-numeric value or an empty model.
#include <cstddef>
#include <map>
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

struct DxfOptions {
  double unit_scale = 1.0;  // metres per drawing unit
};

// What the reader saw, for logs and the compile report.
struct DxfStats {
  std::size_t faces = 0;                       // 3DFACE entities turned into polygons
  std::size_t triangles = 0;                   // of which triangles (corner 4 == corner 3)
  std::size_t degenerate = 0;                  // 3DFACE entities skipped: fewer than 3 distinct corners
  std::map<std::string, std::size_t> skipped;  // other entity types in ENTITIES, by type (TEXT, LINE...)
  std::size_t lines = 0;
};

[[nodiscard]] model::Model read_dxf(const std::string& path, const DxfOptions& options = {});
// The same, also filling `stats` (may be null).
[[nodiscard]] model::Model read_dxf(const std::string& path, const DxfOptions& options, DxfStats* stats);

}  // namespace walk::compiler
