#pragma once
// A sight line through glass: the polygons a ray meets up to and including the first one it cannot see
// through (glass is see-through for visibility, so what lies behind a window is visible).
#include <cstdint>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

// Sheets of glass one sight line passes at most (double glazing, two facades and some): beyond, it stops.
inline constexpr int kMaxGlassLayers = 16;

// Appends the polygon ids met by `ray` to `ids`; `glass[id]` says which polygons are see-through. Returns
// the last hit: the polygon the sight line stops at (or the last glass when it runs out of layers), or no hit
// when it leaves the model.
RayHit trace_through_glass(const RayCaster& caster, Ray ray, const std::vector<char>& glass,
                           std::vector<std::uint32_t>& ids);

}  // namespace walk::compiler
