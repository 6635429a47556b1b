#include "render/albedo_maps.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "model/error.hpp"
#include "render/gl_check.hpp"

namespace walk::render {
namespace {

const char* const kVertexHelpers = R"glsl(
uniform samplerBuffer u_texture_maps;  // per polygon: u plane, v plane, (1 / mean, layer)
out vec2 v_uv;
flat out float v_layer;
flat out vec3 v_modulation;
void albedo_map(uint polygon, vec3 position) {
  v_uv = vec2(0.0);
  v_layer = -1.0;
  v_modulation = vec3(1.0);
  if (polygon == 0xFFFFFFFFu) return;  // a marker, not a surface
  int t = int(polygon) * 3;
  vec4 u = texelFetch(u_texture_maps, t);
  vec4 v = texelFetch(u_texture_maps, t + 1);
  vec4 m = texelFetch(u_texture_maps, t + 2);
  v_uv = vec2(dot(u.xyz, position) + u.w, dot(v.xyz, position) + v.w);
  v_modulation = m.rgb;
  v_layer = m.w;
}
)glsl";

// Maps come in with the patches (u_patch_weight, shared with the vertex stage): the flat moving levels draw
// none, since sampling costs llvmpipe 7-15 ms a 1280x720 frame (Sibenik), more than the levels save. The
// branch is on a uniform, so the lookup inside keeps its derivatives; within it the map is sampled whatever
// the layer (a lookup under a per-pixel branch would have none), then dropped for polygons without one.
const char* const kFragmentHelpers = R"glsl(
uniform sampler2DArray u_albedo_maps;
uniform float u_patch_weight;
in vec2 v_uv;
flat in float v_layer;
flat in vec3 v_modulation;
vec3 albedo_modulation() {
  if (u_patch_weight <= 0.0) return vec3(1.0);
  vec3 texel = texture(u_albedo_maps, vec3(v_uv, max(v_layer, 0.0))).rgb;
  return v_layer < 0.0 ? vec3(1.0) : mix(vec3(1.0), texel * v_modulation, u_patch_weight);
}
)glsl";

// One layer of `size` x `size` from a texture of any size: bilinear, wrapping like GL_REPEAT, on the
// stored sRGB bytes (the layer is a display copy; the mean the light was solved with is the bundle's).
void resample(const std::uint8_t* src, std::uint32_t w, std::uint32_t h, int size, std::uint8_t* out) {
  for (int y = 0; y < size; ++y) {
    const double sy = (y + 0.5) * h / size - 0.5;
    const double fy = std::floor(sy);
    const double ty = sy - fy;
    const std::uint32_t y0 = std::uint32_t((std::int64_t(fy) % h + h) % h), y1 = (y0 + 1) % h;
    for (int x = 0; x < size; ++x) {
      const double sx = (x + 0.5) * w / size - 0.5;
      const double fx = std::floor(sx);
      const double tx = sx - fx;
      const std::uint32_t x0 = std::uint32_t((std::int64_t(fx) % w + w) % w), x1 = (x0 + 1) % w;
      for (int c = 0; c < 4; ++c) {
        const auto at = [&](std::uint32_t xx, std::uint32_t yy) {
          return double(src[(yy * w + xx) * 4 + c]);
        };
        const double top = at(x0, y0) * (1 - tx) + at(x1, y0) * tx;
        const double bottom = at(x0, y1) * (1 - tx) + at(x1, y1) * tx;
        out[(std::size_t(y) * size + x) * 4 + c] =
            static_cast<std::uint8_t>(std::clamp(std::lround(top * (1 - ty) + bottom * ty), 0L, 255L));
      }
    }
  }
}

}  // namespace

std::string with_albedo_maps(const std::string& source, bool vertex_stage) {
  const std::size_t line_end = source.find('\n');
  return source.substr(0, line_end + 1) + "#define WALK_ALBEDO_MAPS 1\n" +
         (vertex_stage ? kVertexHelpers : kFragmentHelpers) + source.substr(line_end + 1);
}

AlbedoMaps::AlbedoMaps(const model::Bundle& bundle) {
  const auto textures = bundle.textures();
  const auto texels = bundle.texels();
  GLint max_size = 0, max_layers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  if (textures.size() > std::size_t(max_layers))
    throw Error("bundle '" + bundle.path() + "' has " + std::to_string(textures.size()) +
                " albedo maps; this GL holds at most " + std::to_string(max_layers) +
                " in one texture array (merge materials that share a map)");
  std::uint32_t longest = 1;
  for (const auto& t : textures) longest = std::max({longest, t.width, t.height});
  size_ = int(std::min<std::uint32_t>(longest, std::uint32_t(max_size)));
  std::vector<std::uint8_t> layers(std::size_t(size_) * size_ * 4 * textures.size());
  for (std::size_t i = 0; i < textures.size(); ++i)
    resample(texels.data() + textures[i].first_byte, textures[i].width, textures[i].height, size_,
             layers.data() + std::size_t(size_) * size_ * 4 * i);
  glGenTextures(1, &array_);
  glBindTexture(GL_TEXTURE_2D_ARRAY, array_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // sRGB storage: the sampler returns linear light, filtered in linear light.
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_SRGB8_ALPHA8, size_, size_, GLsizei(textures.size()), 0, GL_RGBA,
               GL_UNSIGNED_BYTE, layers.data());
  glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);

  std::vector<float> maps;
  maps.reserve(bundle.polygon_textures().size() * 12);
  for (const auto& p : bundle.polygon_textures()) {
    maps.insert(maps.end(), {p.u[0], p.u[1], p.u[2], p.u[3], p.v[0], p.v[1], p.v[2], p.v[3]});
    if (p.texture == model::kNoTextureRecord) {
      maps.insert(maps.end(), {1.0f, 1.0f, 1.0f, -1.0f});
    } else {
      const auto& m = textures[p.texture].mean;
      maps.insert(maps.end(), {1.0f / m[0], 1.0f / m[1], 1.0f / m[2], float(p.texture)});
    }
  }
  glGenBuffers(1, &maps_buffer_);
  glBindBuffer(GL_TEXTURE_BUFFER, maps_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<std::size_t>(maps.size() * sizeof(float), 16)),
               maps.empty() ? nullptr : maps.data(), GL_STATIC_DRAW);
  glGenTextures(1, &maps_texture_);
  glBindTexture(GL_TEXTURE_BUFFER, maps_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, maps_buffer_);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  check_gl("uploading the albedo maps");
}

AlbedoMaps::~AlbedoMaps() {
  glDeleteTextures(1, &maps_texture_);
  glDeleteBuffers(1, &maps_buffer_);
  glDeleteTextures(1, &array_);
}

void AlbedoMaps::point_samplers(GLuint program) {
  glUniform1i(glGetUniformLocation(program, "u_texture_maps"), kTextureMapsUnit);
  glUniform1i(glGetUniformLocation(program, "u_albedo_maps"), kAlbedoArrayUnit);
}

void AlbedoMaps::bind() const {
  glActiveTexture(GL_TEXTURE0 + kTextureMapsUnit);
  glBindTexture(GL_TEXTURE_BUFFER, maps_texture_);
  glActiveTexture(GL_TEXTURE0 + kAlbedoArrayUnit);
  glBindTexture(GL_TEXTURE_2D_ARRAY, array_);
  glActiveTexture(GL_TEXTURE0);
}

void AlbedoMaps::unbind() {
  glActiveTexture(GL_TEXTURE0 + kTextureMapsUnit);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glActiveTexture(GL_TEXTURE0 + kAlbedoArrayUnit);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace walk::render
