#pragma once
// `walk export radiance`: a compiled bundle as a Radiance scene, so anyone can check our light with the
// field's reference tool (`oconv scene.rad > scene.oct; rtrace -I`). Geometry: every drawn triangle as a
// `polygon` in world metres; materials: `plastic` with the bundle's reflectance, `glass` for glazing;
// luminaires: panels as `light` polygons, point lights as small `light` spheres, spots as `spotlight`
// spheres, all carrying the radiant watts per channel the solver used (Radiance's 179 lm/W convention is
// ours, so its lux are ours). Measured fixtures are written as isotropic spheres of their flux, named so
// (their tables are for ies2rad).
#include <cstddef>
#include <string>

#include "model/bundle.hpp"

namespace walk::compiler {

struct RadianceExportStats {
  std::size_t materials = 0;
  std::size_t polygons = 0;  // surface triangles
  std::size_t panels = 0;
  std::size_t spheres = 0;  // point, spot and fixture lights
  std::size_t fixtures_approximated = 0;
};

// Writes `folder`/scene.rad (made if missing) whole or not at all; throws walk::Error naming the path.
RadianceExportStats export_radiance(const model::Bundle& bundle, const std::string& folder);

}  // namespace walk::compiler
