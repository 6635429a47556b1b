#pragma once
// Minimal Wavefront OBJ reader for the ray-casting benchmark and tests only (not an importer: no materials,
// groups or normals): `v` and `f` lines, faces fanned into triangles, polygon id = face number.
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/raycast/triangle_bvh.hpp"
#include "model/error.hpp"

namespace walk::bench {

// `scale` multiplies coordinates (metres per OBJ unit); `polygons` receives the face count.
inline std::vector<compiler::Triangle> read_obj_triangles(const std::string& path, double scale,
                                                          std::size_t* polygons = nullptr) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  std::vector<model::Vec3> v;
  std::vector<compiler::Triangle> out;
  std::vector<std::uint32_t> face;
  std::string line;
  std::uint32_t faces = 0;
  while (std::getline(in, line)) {
    if (line.size() < 2) continue;
    if (line[0] == 'v' && line[1] == ' ') {
      const char* p = line.c_str() + 2;
      char* end = nullptr;
      model::Vec3 x;
      for (int a = 0; a < 3; ++a) {
        x[a] = std::strtod(p, &end) * scale;
        p = end;
      }
      v.push_back(x);
    } else if (line[0] == 'f' && line[1] == ' ') {
      face.clear();
      std::istringstream ss(line.substr(2));
      std::string tok;
      while (ss >> tok) {
        const long i = std::strtol(tok.c_str(), nullptr, 10);  // stops at the first '/'
        const long k = i < 0 ? static_cast<long>(v.size()) + i : i - 1;
        if (k < 0 || k >= static_cast<long>(v.size())) throw Error(path + ": face index out of range");
        face.push_back(static_cast<std::uint32_t>(k));
      }
      for (std::size_t j = 1; j + 1 < face.size(); ++j)
        out.push_back({v[face[0]], v[face[j]], v[face[j + 1]], faces});
      ++faces;
    }
  }
  if (polygons) *polygons = faces;
  return out;
}

}  // namespace walk::bench
