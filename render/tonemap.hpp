#pragma once
// The fragment stage: radiosity divided by the exposure (W/m2 shown as white), clamped, sRGB encoded.
// Encoding in the shader rather than through GL_FRAMEBUFFER_SRGB keeps the FBO plain RGBA8, so every backend
// reads back the same bytes.
#include <array>
#include <string>

namespace walk::render {

// GLSL (no #version line): vec3 srgb_encode(vec3 linear), clamped to 0..1 first. Shared by the scene and
// the accumulation resolve, so both encode alike.
extern const char* const kSrgbEncodeGlsl;
// Input: v_radiosity (linear W/m2); uniforms u_inv_exposure, u_opacity (1 except for glass).
extern const std::string kTonemapFragmentShader;
// The sRGB transfer function's inverse at each 8-bit code: display bytes back to linear light (0..1).
[[nodiscard]] std::array<float, 256> srgb_decode_table();

}  // namespace walk::render
