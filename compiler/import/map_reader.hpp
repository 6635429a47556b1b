#pragma once
// Quake .map levels (standard and Valve 220) to a Model. Brushes become faces by plane intersection, faces
// hidden inside other brushes of the same entity are removed (CSG), `clip` brushes and `trigger_*` entities
// are skipped, sky faces are black (reflectance 0: light leaving through them is lost, nothing is seen
// through them), the world's solid brushes are the model's solids (the cells stage's), liquids ('*' textures)
// are glass. `func_door` and `func_door_secret` brushes become openings. Each texture gets a material whose
// reflectance is a hash of its name (no WAD files are read). `light*` entities become point (or, with a
// `target`, spot) luminaires; lights that share a `targetname`, or else a non-zero `style`, form one circuit;
// the rest form the circuit "static".
#include <cstddef>
#include <istream>
#include <string>

#include "compiler/import/brush_csg.hpp"
#include "compiler/import/brush_geometry.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Radiant watts per unit of a Quake light's "light" value: the default 300 becomes a 60 W lamp, about the
// light such a lamp puts into a Quake-sized room (light.exe's linear falloff reaches 0 at 300 units = 7.6 m).
inline constexpr double kWattsPerQuakeLight = 0.2;

struct MapOptions {
  double unit_scale = 0.0254;  // metres per map unit (Quake units are inches)
};

struct MapStats {
  std::size_t entities = 0;
  std::size_t brushes = 0;       // in the file
  std::size_t brush_planes = 0;  // plane lines in the file
  std::size_t brushes_built = 0;
  std::size_t clip_brushes = 0;     // skipped: collision only
  std::size_t trigger_brushes = 0;  // skipped: trigger_* entities
  std::size_t door_brushes = 0;     // func_door, func_door_secret: openings
  std::size_t sky_faces = 0;
  std::size_t liquid_faces = 0;
  std::size_t lights = 0;
  std::size_t spot_lights = 0;
  bool valve220 = false;
  BrushStats brush;
  CsgStats csg;
};

[[nodiscard]] model::Model read_map(const std::string& path, const MapOptions& options = {},
                                    MapStats* stats = nullptr);
[[nodiscard]] model::Model read_map_text(const std::string& text, const std::string& file,
                                         const MapOptions& options, MapStats* stats);

// Reflectance of a texture: a deterministic colour from its name, 0.2..0.8 per channel.
[[nodiscard]] model::Rgb texture_reflectance(const std::string& texture);

}  // namespace walk::compiler
