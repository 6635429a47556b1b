#pragma once
// Quake .map text to entities: key/value pairs and brushes, each brush a list of planes given by three points
// (standard format) with a texture name; Valve 220 texture axes ("[ ux uy uz off ]") are read and ignored.
// Knows nothing of geometry beyond the plane points. Errors name the file and the line.
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

struct MapPlane {
  std::array<model::Vec3, 3> points{};  // in file units; the normal is (p0 - p1) x (p2 - p1), pointing out
  std::string texture;
  std::size_t line = 0;
};

struct MapBrush {
  std::vector<MapPlane> planes;
  std::size_t line = 0;  // line of its opening brace
};

struct MapEntity {
  std::map<std::string, std::string> keys;
  std::vector<MapBrush> brushes;
  std::size_t line = 0;
  [[nodiscard]] std::string get(const std::string& key, const std::string& fallback = {}) const {
    const auto it = keys.find(key);
    return it == keys.end() ? fallback : it->second;
  }
};

struct MapFile {
  std::vector<MapEntity> entities;
  bool valve220 = false;
};

// Most planes one brush may have: hand-built brushes have 4 to a few dozen; this bounds the quadratic face
// building on hostile input.
inline constexpr std::size_t kMaxBrushPlanes = 256;

[[nodiscard]] MapFile parse_map(const std::string& text, const std::string& file);

}  // namespace walk::compiler
