#pragma once
// The fragment stage: radiosity divided by the exposure (W/m2 shown as white), clamped, sRGB encoded.
// Encoding in the shader rather than through GL_FRAMEBUFFER_SRGB keeps the FBO plain RGBA8, so every backend
// reads back the same bytes.
namespace walk::render {

// Input: v_radiosity (linear W/m2); uniforms u_inv_exposure, u_opacity (1 except for glass).
extern const char* const kTonemapFragmentShader;

}  // namespace walk::render
