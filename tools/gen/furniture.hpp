#pragma once
// Furniture cut from a furnished room model (the LBNL conference room): the file groups faces by material,
// not by object, so objects are found as its connected pieces (faces whose corners lie within
// kPieceGap of each other) grouped by proximity, plus a thin slab (a table top) joined to the pieces that
// stand under it. Objects that stand on the floor, are at most 3 m across and tall enough to matter become
// the catalogue, one entry per distinct shape, each keeping its faces' materials.
#include <string>
#include <vector>

#include "model/model.hpp"

namespace walk::gen {

// Corners of two pieces closer than this belong to one object, metres: the conference room's chair parts
// sit 2-10 mm apart while separate chairs and the table stand centimetres apart.
inline constexpr double kPieceGap = 0.015;

// An indexed mesh in the object's own frame: centred on its footprint, standing on z = 0.
struct FurnitureObject {
  std::string name;  // "object N" (N: first face in the file), for the scene's group names
  std::vector<model::Vec3> vertices;
  struct Face {
    std::vector<std::uint32_t> corners;
    std::uint32_t material = 0;  // index into FurnitureCatalogue::materials
  };
  std::vector<Face> faces;
  model::Vec3 size{0.0};  // extent along x, y and z, metres
  std::size_t triangles = 0;
};

struct FurnitureCatalogue {
  std::vector<model::Material> materials;  // the source file's, reflectance from its diffuse colour
  std::vector<FurnitureObject> objects;    // distinct shapes, in the order they appear in the file
  std::size_t pieces = 0;                  // objects found (before selection and dedup)
  std::size_t standing = 0;                // of which stand on the floor and fit the size limits
};

// Reads the OBJ at `path` (metres per file unit `scale`, y up as OBJ files are) and cuts its furniture.
// Throws walk::Error naming the file when it cannot be read or holds no object that qualifies.
[[nodiscard]] FurnitureCatalogue cut_furniture(const std::string& path, double scale);

}  // namespace walk::gen
