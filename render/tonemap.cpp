#include "render/tonemap.hpp"

namespace walk::render {

const char* const kTonemapFragmentShader = R"glsl(#version 330 core
in vec3 v_radiosity;
uniform float u_inv_exposure;
uniform float u_opacity;
out vec4 o_colour;

vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 low = c * 12.92;
  vec3 high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), c));
}

void main() { o_colour = vec4(srgb_encode(v_radiosity * u_inv_exposure), u_opacity); }
)glsl";

}  // namespace walk::render
