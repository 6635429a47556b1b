#pragma once
// The vertex stage: mixes each vertex's per-circuit radiosity by the dimmer levels, so a dimmer change costs
// one uniform upload and no buffer traffic.
namespace walk::render {

inline constexpr int kMaxCircuits = 64;  // size of the u_levels uniform array

// Inputs: a_position (location 0), a_albedo (location 1), a_polygon (location 2, integer); u_light: R32F
// texture buffer laid out like LGHT, [vertex][circuit][3], indexed by gl_VertexID; u_polygon_light: PLGT
// already mixed by the dimmer levels on the CPU, [polygon][3], indexed by a_polygon; u_patch_weight blends
// the two linearly. Output: v_radiosity, linear W/m2.
extern const char* const kLightMixerVertexShader;

}  // namespace walk::render
