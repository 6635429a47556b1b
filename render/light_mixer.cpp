#include "render/light_mixer.hpp"

#include "model/compact_code.hpp"

namespace walk::render {

static_assert(model::kCompactStops == 16.0, "the vertex shader decodes LINT with 16 stops written out");

// R32F with three fetches: RGB32F texture buffers need GL 4.0, and padding to RGBA32F would cost a third
// more memory than the bundle's own LGHT layout, which is uploaded as is.
const char* const kLightMixerVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_albedo;
layout(location = 2) in uint a_polygon;
uniform mat4 u_view_projection;
uniform samplerBuffer u_light;          // per vertex: the radiosity patches of the circuits shown full
uniform samplerBuffer u_polygon_light;  // per polygon, already mixed (RGB): the coarse display while moving
uniform float u_patch_weight;           // 0: coarse, 1: patches, between: the blend after stopping
uniform int u_circuit_count;  // circuits shown full
uniform float u_levels[64];
// Circuits shown compact (render/display_light.hpp): colour x sum(level x scale x the code's value,
// model/compact_code.hpp: 2^((code - 255) x 16 / 254), 0 for code 0).
uniform samplerBuffer u_compact_colour;  // RGBA8 per vertex
uniform samplerBuffer u_compact_code;    // R8 [vertex][compact circuit]
uniform int u_compact_count;
uniform float u_compact_levels[64];  // level x scale
uniform float u_ambient;
uniform vec4 u_clip_plane;  // the map view cuts away what is above the viewer's storey (GL_CLIP_DISTANCE0)
out vec3 v_radiosity;

vec3 mixed(samplerBuffer light, int base) {
  vec3 sum = vec3(0.0);
  for (int c = 0; c < u_circuit_count; ++c) {
    int i = base + c * 3;
    sum += u_levels[c] * vec3(texelFetch(light, i).r, texelFetch(light, i + 1).r, texelFetch(light, i + 2).r);
  }
  return sum;
}

vec3 compact_mixed(int vertex) {
  float sum = 0.0;
  int base = vertex * u_compact_count;
  for (int c = 0; c < u_compact_count; ++c) {
    float code = texelFetch(u_compact_code, base + c).r * 255.0;
    sum += code > 0.5 ? u_compact_levels[c] * exp2((code - 255.0) * (16.0 / 254.0)) : 0.0;
  }
  return u_compact_count > 0 ? sum * texelFetch(u_compact_colour, vertex).rgb : vec3(0.0);
}

void main() {
  // Each end skips the fetches it does not need: coarse frames read one polygon's values per vertex.
  vec3 fine = u_patch_weight > 0.0 ? mixed(u_light, gl_VertexID * u_circuit_count * 3) + compact_mixed(gl_VertexID)
                                   : vec3(0.0);
  // Three fetches instead of three per circuit: with 16 circuits the vertex stage is most of a frame.
  int p = int(a_polygon) * 3;
  vec3 coarse = u_patch_weight < 1.0 ? vec3(texelFetch(u_polygon_light, p).r, texelFetch(u_polygon_light, p + 1).r,
                                            texelFetch(u_polygon_light, p + 2).r)
                                     : vec3(0.0);
  v_radiosity = a_albedo * u_ambient + mix(coarse, fine, u_patch_weight);
  gl_Position = u_view_projection * vec4(a_position, 1.0);
  gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));
#ifdef WALK_ALBEDO_MAPS
  albedo_map(a_polygon, a_position);
#endif
}
)glsl";

}  // namespace walk::render
