#include "render/light_mixer.hpp"

namespace walk::render {

// R32F with three fetches: RGB32F texture buffers need GL 4.0, and padding to RGBA32F would cost a third
// more memory than the bundle's own LGHT layout, which is uploaded as is.
const char* const kLightMixerVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_albedo;
uniform mat4 u_view_projection;
uniform samplerBuffer u_light;
uniform int u_circuit_count;
uniform float u_levels[64];
uniform float u_ambient;
out vec3 v_radiosity;

void main() {
  vec3 radiosity = a_albedo * u_ambient;
  int base = gl_VertexID * u_circuit_count * 3;
  for (int c = 0; c < u_circuit_count; ++c) {
    int i = base + c * 3;
    vec3 light = vec3(texelFetch(u_light, i).r, texelFetch(u_light, i + 1).r, texelFetch(u_light, i + 2).r);
    radiosity += u_levels[c] * light;
  }
  v_radiosity = radiosity;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)glsl";

}  // namespace walk::render
