#pragma once
// The vertex stage: mixes each vertex's per-circuit radiosity by the dimmer levels, so a dimmer change costs
// one upload of a float a circuit and no other buffer traffic.
#include <string>

namespace walk::render {

// Circuits the u_levels texture buffer holds: GL 3.3 guarantees 65,536 texels in a texture buffer, and
// the entries' encodings (render/display_light.hpp) keep circuit indices exact far past it.
inline constexpr int kMaxCircuits = 65536;

// Inputs: a_position (location 0), a_albedo (location 1), a_polygon (location 2, integer), a_light_first
// (location 3, uvec2: the vertex's first full and first compact entry, render/display_light.hpp).
// u_light: RGBA32F texture buffer of full entries (radiosity, circuit); u_compact_code: R32UI texture
// buffer of compact entries (circuit << 8 | code) and u_compact_colour (RGBA8 per vertex); both mixed by
// u_levels, an R32F texture buffer indexed by circuit (a compact circuit's level times its scale).
// u_polygon_light (RGBA32F) and u_polygon_first (R32UI, per polygon, indexed by a_polygon): PLGT's entries,
// mixed by u_levels the same way; u_patch_weight blends the two linearly. Output: v_radiosity, linear W/m2
// (flat light: the displayed sRGB colour, below).
extern const std::string kLightMixerVertexShader;

// `source` (this vertex shader or render/tonemap.hpp's fragment shader) with v_radiosity flat: each
// triangle shows its provoking vertex's light, as the coarse form's shared vertices need
// (render/cluster_layout.hpp), exposed and encoded by the vertex stage (u_inv_exposure) and written as it is
// by the fragment stage. Not with albedo maps.
[[nodiscard]] std::string with_flat_light(const std::string& source);

}  // namespace walk::render
