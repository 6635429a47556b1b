#pragma once
// A sight line through glass: the polygons a ray meets up to and including the first one it cannot see
// through (glass is see-through for visibility, so what lies behind a window is visible).
#include <cstdint>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

// Sheets of glass one sight line passes at most (double glazing, two facades and some): beyond, it stops.
inline constexpr int kMaxGlassLayers = 16;

// Appends the polygon ids met by `ray` to `ids`; `glass[id]` says which polygons are see-through. With
// `cull_back_faces` (the renderer's default) a polygon met from behind is passed through and not listed:
// the renderer does not draw it, and shows what lies behind. Returns the last hit: the polygon the sight
// line stops at (or the last glass or back face when it runs out of layers), or no hit when it leaves the
// model. Seeing past back faces relies on the caster's tie rule: of two back-to-back polygons the one facing
// the ray must win (the axial and brute-force casters keep it; the BVH and Embree do not).
RayHit trace_through_glass(const RayCaster& caster, Ray ray, const std::vector<char>& glass,
                           std::vector<std::uint32_t>& ids, bool cull_back_faces = false);

}  // namespace walk::compiler
