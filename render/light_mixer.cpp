#include "render/light_mixer.hpp"

#include <cstdint>

#include "model/compact_code.hpp"
#include "render/display_light.hpp"
#include "render/tonemap.hpp"

namespace walk::render {

static_assert(model::kCompactStops == 16.0, "the vertex shader decodes LINT with 16 stops written out");
static_assert(kMaxCircuits == 65536, "kMaxEntries in the shader below");
static_assert(kMaxCircuits < std::uint32_t(kLastFullEntry),
              "a full entry's circuit plus kLastFull stays exact in a float");
static_assert(std::uint64_t(kMaxCircuits) << 8 < kLastCompactEntry,
              "a compact entry's circuit << 8 stays below its last mark");

// Each vertex loops over its own entries only (render/display_light.hpp), one texel each: the full entry's
// RGBA32F holds radiosity and circuit together.
const std::string kLightMixerVertexShader = std::string(R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_albedo;
layout(location = 2) in uint a_polygon;
layout(location = 3) in uvec2 a_light_first;  // first full entry, first compact entry (kNone: none)
uniform mat4 u_view_projection;
uniform samplerBuffer u_light;          // full entries: radiosity (rgb) and circuit (a)
uniform samplerBuffer u_polygon_light;  // the polygons' full entries (the coarse display while moving)
uniform usamplerBuffer u_polygon_first;  // per polygon, its first entry in u_polygon_light (kNone: none)
uniform float u_patch_weight;           // 0: coarse, 1: patches, between: the blend after stopping
uniform samplerBuffer u_levels;         // R32F per circuit; a compact circuit's times its scale
// Circuits shown compact (render/display_light.hpp): colour x sum(level x scale x the code's value,
// model/compact_code.hpp: 2^((code - 255) x 16 / 254), 0 for code 0).
uniform samplerBuffer u_compact_colour;  // RGBA8 per vertex
uniform usamplerBuffer u_compact_code;   // compact entries: circuit << 8 | code
uniform float u_ambient;
uniform vec4 u_clip_plane;  // the map view cuts away what is above the viewer's storey (GL_CLIP_DISTANCE0)
#ifdef WALK_FLAT_LIGHT
// The provoking vertex's (the coarse form ends each triangle on its polygon's), already shown: exposed and
// sRGB encoded here, once a vertex, where the fragment stage would do it at every fragment of the triangle
// for the same value (llvmpipe's fragment work is most of a moving frame). Never with albedo maps.
flat out vec3 v_radiosity;
uniform float u_inv_exposure;
#else
out vec3 v_radiosity;
#endif
)glsl") + kSrgbEncodeGlsl + R"glsl(

const uint kNone = 0xffffffffu;
const float kLastFull = 1048576.0;       // added to a vertex's last full entry's circuit
const uint kLastCompact = 0x80000000u;  // set on a vertex's last compact entry
const uint kMaxEntries = 65536u;        // kMaxCircuits: a bound for the compiler, never reached

float level(uint circuit) { return texelFetch(u_levels, int(circuit)).r; }

// Level x radiosity over a run of full entries from `first`, up to the one marked last.
vec3 sum_full(samplerBuffer entries, uint first) {
  vec3 sum = vec3(0.0);
  if (first == kNone) return sum;
  for (uint i = first; i < first + kMaxEntries; ++i) {
    vec4 entry = texelFetch(entries, int(i));
    bool last = entry.a >= kLastFull;
    sum += level(uint(last ? entry.a - kLastFull : entry.a)) * entry.rgb;
    if (last) break;
  }
  return sum;
}

vec3 mixed() { return sum_full(u_light, a_light_first.x); }

vec3 compact_mixed(int vertex) {
  if (a_light_first.y == kNone) return vec3(0.0);
  float sum = 0.0;
  for (uint i = a_light_first.y; i < a_light_first.y + kMaxEntries; ++i) {
    uint entry = texelFetch(u_compact_code, int(i)).r;
    sum += level((entry & ~kLastCompact) >> 8u) * exp2((float(entry & 255u) - 255.0) * (16.0 / 254.0));
    if ((entry & kLastCompact) != 0u) break;
  }
  return sum * texelFetch(u_compact_colour, vertex).rgb;
}

void main() {
  // Each end skips the fetches it does not need: coarse frames read one polygon's values per vertex.
  vec3 fine = u_patch_weight > 0.0 ? mixed() + compact_mixed(gl_VertexID)
                                   : vec3(0.0);
  // The polygon's own circuits only, as a vertex's: a dimmer turned while walking is one upload of the levels.
  vec3 coarse = u_patch_weight < 1.0 ? sum_full(u_polygon_light, texelFetch(u_polygon_first, int(a_polygon)).r)
                                     : vec3(0.0);
  v_radiosity = a_albedo * u_ambient + mix(coarse, fine, u_patch_weight);
#ifdef WALK_FLAT_LIGHT
  v_radiosity = srgb_encode(v_radiosity * u_inv_exposure);
#endif
  gl_Position = u_view_projection * vec4(a_position, 1.0);
  gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));
#ifdef WALK_ALBEDO_MAPS
  albedo_map(a_polygon, a_position);
#endif
}
)glsl";

std::string with_flat_light(const std::string& source) {
  const std::size_t line_end = source.find('\n');
  return source.substr(0, line_end + 1) + "#define WALK_FLAT_LIGHT 1\n" + source.substr(line_end + 1);
}

}  // namespace walk::render
