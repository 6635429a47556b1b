#pragma once
// DXF import for buildings. Surfaces: 3DFACE, SOLID/TRACE, POLYLINE polyface and polygon meshes, and LINE,
// ARC, CIRCLE, LWPOLYLINE and 2D POLYLINE given a thickness (extruded along their OCS normal). INSERT places
// blocks, nested, with scale (negative too: mirrored faces keep their outward side), rotation and column/row
// arrays. Layers become model groups; colours resolve BYLAYER/BYBLOCK; true colours (code 420) become
// materials; $INSUNITS sets the unit when the scene does not. Zero-thickness lines and outlines are returned
// as wires for 2D floor plans. Every error names the file and the line.
#include <cstddef>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct DxfOptions {
  double unit_scale = 1.0;    // metres per drawing unit
  bool use_insunits = false;  // true: the file's $INSUNITS, when present and not 0, overrides unit_scale
};

// What the reader saw, for logs and the compile report.
struct DxfStats {
  std::size_t faces = 0;                       // polygons produced
  std::size_t triangles = 0;                   // of which triangles
  std::size_t degenerate = 0;                  // faces skipped: fewer than 3 distinct corners or no area
  std::map<std::string, std::size_t> skipped;  // entity types with no geometry we read (TEXT, HATCH...)
  std::map<std::string, std::size_t> read;     // entity types that gave geometry, per instance drawn
  std::size_t block_instances = 0;             // blocks placed by INSERT (each array cell counts)
  std::size_t mirrored_instances = 0;          // of which with a negative determinant (mirrored)
  std::size_t frozen = 0;                      // entities skipped on frozen layers or in paper space
  std::size_t wires = 0;                       // zero-thickness segments
  std::size_t true_colours = 0;                // faces whose colour came from code 420
  std::optional<int> insunits;                 // $INSUNITS when the header has it
  double unit_scale = 1.0;                     // metres per unit actually used
  std::size_t lines = 0;
};

// A zero-thickness segment (LINE, an outline's edge), in metres: what 2D floor plans are drawn with.
struct DxfWire {
  model::Vec3 a{0.0}, b{0.0};
  std::uint32_t group = 0;  // layer, as a model group
  std::uint32_t source_line = 0;
};

// Metres per unit for a $INSUNITS code; nullopt for 0 (unitless) and unknown codes.
[[nodiscard]] std::optional<double> insunits_metres(int code);

[[nodiscard]] model::Model read_dxf(const std::string& path, const DxfOptions& options = {});
// The same, also filling `stats` (may be null). Throws walk::Error when the file has no surfaces.
[[nodiscard]] model::Model read_dxf(const std::string& path, const DxfOptions& options, DxfStats* stats);
// From a stream (`file` names it in errors); fills `wires` when given and then accepts a file without
// surfaces (a 2D plan). `stats` and `wires` may be null.
[[nodiscard]] model::Model read_dxf(std::istream& in, const std::string& file, const DxfOptions& options,
                                    DxfStats* stats, std::vector<DxfWire>* wires);

}  // namespace walk::compiler
