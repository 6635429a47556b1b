#include "render/tonemap.hpp"

#include <string>

#include "model/srgb.hpp"

namespace walk::render {

const char* const kSrgbEncodeGlsl = R"glsl(
// sRGB's 1/2.4 power from three square roots (Taylor's fit): within 0.25/255 of the exact curve, and
// cheaper than pow(), which llvmpipe evaluates as exp2(log2()) polynomials: about 2.5 ms less per 1280x720
// frame on 2 cores.
vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 s1 = sqrt(c);
  vec3 s2 = sqrt(s1);
  vec3 s3 = sqrt(s2);
  vec3 high = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c;
  return mix(c * 12.92, high, step(vec3(0.0031308), c));
}
)glsl";

const std::string kTonemapFragmentShader = std::string(R"glsl(#version 330 core
#ifdef WALK_FLAT_LIGHT
flat in vec3 v_radiosity;
#else
in vec3 v_radiosity;
#endif
uniform float u_inv_exposure;
uniform float u_opacity;
out vec4 o_colour;
)glsl") + kSrgbEncodeGlsl + R"glsl(
void main() {
#ifdef WALK_FLAT_LIGHT
#ifdef WALK_ALBEDO_MAPS
#error flat light is encoded per vertex, which albedo maps would modulate per fragment
#endif
  o_colour = vec4(v_radiosity, u_opacity);  // encoded by the vertex stage (render/light_mixer.hpp)
#else
  vec3 radiosity = v_radiosity;
#ifdef WALK_ALBEDO_MAPS
  radiosity *= albedo_modulation();
#endif
  o_colour = vec4(srgb_encode(radiosity * u_inv_exposure), u_opacity);
#endif
}
)glsl";

std::array<float, 256> srgb_decode_table() {
  std::array<float, 256> table{};
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = float(model::srgb_decode_table()[i]);
  return table;
}

}  // namespace walk::render
