#pragma once
// Mesh formats through assimp (OBJ, glTF 2.0, 3DS, PLY, COLLADA...): node transforms are baked in, identical
// vertices joined, faces kept as the polygons the file gives (clean-up splits non-planar ones). A
// material's diffuse colour becomes its reflectance, times its albedo map's mean where it has one (the map
// itself and each face's texture coordinates, as a TextureMap, are kept for the renderer); faces with an
// emissive material become luminaires (one rectangle per coplanar group of faces in a mesh, radiant power pi
// * emission * area) on one circuit per emissive material, and are not drawn as surfaces. Each mesh (an OBJ
// group) is a model group.
#include <cstddef>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct MeshOptions {
  double unit_scale = 1.0;      // metres per file unit
  bool y_up = false;            // true: the file's y axis is up (OBJ, glTF); turned into our z-up frame
  double emission_scale = 1.0;  // watts per (emission unit x square metre x pi)
  // Where albedo maps are looked for after the model's own folder ([model] textures).
  std::vector<std::string> texture_dirs;
};

struct MeshStats {
  std::size_t meshes = 0;
  std::size_t faces = 0;               // polygons produced
  std::size_t triangles = 0;           // of which triangles
  std::size_t skipped_primitives = 0;  // points and lines
  std::size_t materials = 0;
  std::size_t emissive_faces = 0;
  std::size_t luminaires = 0;
  std::size_t vertices = 0;
  // Albedo maps the materials name (map_Kd, a glTF base colour texture): loaded (once per file) and drawn;
  // a missing or unreadable one is warned about by name and the material's colour used.
  std::size_t textures_named = 0;
  std::size_t textures_loaded = 0;
  std::size_t textures_missing = 0;
  // Faces with a texture map (their material has an albedo map, and the file gave UVs).
  std::size_t faces_textured = 0;
  std::size_t material_libraries_missing = 0;  // OBJ `mtllib` files not beside the model (warned by name)
};

// Throws walk::Error naming the file (assimp reports no line numbers) when assimp cannot read it or it has
// no faces.
[[nodiscard]] model::Model read_mesh(const std::string& path, const MeshOptions& options, MeshStats* stats);

}  // namespace walk::compiler
