#pragma once
// Albedo maps drawn modulated by the light. The radiosity at a vertex is reflectance x irradiance with the
// map's mean in the reflectance (the solver's view of the surface), so a pixel shows radiosity x texel /
// mean: the light's level is kept and the map adds its detail. One GL_TEXTURE_2D_ARRAY holds every map (a
// layer each, resampled to one size), so a frame stays one multi-draw; per polygon, an RGBA32F texture
// buffer holds its coordinate planes and its layer and 1/mean. Texture coordinates are evaluated from the
// vertex position, so every form the renderer draws (patches, coarse, levels of detail, subdivided quads)
// gets them without per-vertex data. A bundle without maps never creates this, and its shaders are compiled
// without the code.
#include <glad/gl.h>

#include <string>

#include "model/bundle.hpp"

namespace walk::render {

// Texture units the scene shaders use for the maps (0 and 1 hold the light buffers).
inline constexpr int kTextureMapsUnit = 2;
inline constexpr int kAlbedoArrayUnit = 3;

// `source` with the albedo-map code enabled: `#define WALK_ALBEDO_MAPS` and the vertex or fragment helpers
// (albedo_map(polygon, position) in the vertex stage; albedo_modulation() in the fragment stage) inserted
// after its #version line.
[[nodiscard]] std::string with_albedo_maps(const std::string& source, bool vertex_stage);

class AlbedoMaps {
 public:
  // Uploads the bundle's maps; the bundle must have them (TEXR). Throws walk::Error naming the bundle when
  // this GL cannot hold them.
  explicit AlbedoMaps(const model::Bundle& bundle);
  ~AlbedoMaps();
  AlbedoMaps(const AlbedoMaps&) = delete;
  AlbedoMaps& operator=(const AlbedoMaps&) = delete;

  // Points a program's two samplers at the maps' units: once per program, which keeps them. Call with the
  // program in use.
  static void point_samplers(GLuint program);
  // Binds both textures to their units for this frame.
  void bind() const;
  static void unbind();

 private:
  GLuint array_ = 0, maps_buffer_ = 0, maps_texture_ = 0;
  int size_ = 0;
};

}  // namespace walk::render
