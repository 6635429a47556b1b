#pragma once
// The vertex stage: mixes each vertex's per-circuit radiosity by the dimmer levels, so a dimmer change costs
// one uniform upload and no buffer traffic.
namespace walk::render {

inline constexpr int kMaxCircuits = 64;  // size of the u_levels uniform array

// Inputs: a_position (location 0), a_albedo (location 1), a_polygon (location 2, integer); u_light: R32F
// texture buffer of the circuits shown full, [vertex][full circuit][3], indexed by gl_VertexID, mixed by
// u_levels; u_compact_colour (RGBA8 per vertex) and u_compact_code (R8, [vertex][compact circuit]) for the
// circuits shown compact, mixed by u_compact_levels (render/display_light.hpp); u_polygon_light: PLGT
// already mixed by the dimmer levels on the CPU, [polygon][3], indexed by a_polygon; u_patch_weight blends
// the two linearly. Output: v_radiosity, linear W/m2.
extern const char* const kLightMixerVertexShader;

}  // namespace walk::render
