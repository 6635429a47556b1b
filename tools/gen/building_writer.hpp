#pragma once
// Collects a building's faces into the parts of its mesh, one per group and material, turning each face so
// that its normal points the way the caller says (faces are built by their corners, so no caller has to get
// the winding right), and counting triangles.
#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tools/gen/building.hpp"
#include "tools/gen/floor_loops.hpp"

namespace walk::gen {

class BuildingWriter {
 public:
  explicit BuildingWriter(Building& b) : b_(b) {}

  // The part's index in Building::parts: a reference would dangle once another part is added.
  std::size_t part_index(const std::string& group, const std::string& material) {
    const auto [it, added] = index_.emplace(std::make_pair(group, material), b_.parts.size());
    if (added) b_.parts.push_back({group, material, {}, {}});
    return it->second;
  }
  MeshPart& part(const std::string& group, const std::string& material) {
    return b_.parts[part_index(group, material)];
  }

  // A planar face turned so that its normal points along `facing` (a face is built by its corners and
  // turned here, so no caller has to get the winding right).
  void face(const std::string& group, const std::string& material, std::vector<model::Vec3> loop,
            model::Vec3 facing, bool wall = false) {
    if (glm::dot(model::area_vector(loop), facing) < 0.0) std::reverse(loop.begin(), loop.end());
    MeshPart& p = part(group, material);
    std::vector<std::uint32_t> corners;
    for (const model::Vec3& v : loop) {
      corners.push_back(static_cast<std::uint32_t>(p.vertices.size()));
      p.vertices.push_back(v);
    }
    p.faces.push_back(std::move(corners));
    b_.triangles += loop.size() - 2;
    b_.structure_triangles += loop.size() - 2;
    if (wall) {
      model::Polygon poly;
      poly.vertices = std::move(loop);
      poly.name = group;
      b_.walls.push_back(std::move(poly));
    }
  }

  // A vertical rectangle over a-b from z0 to z1, facing `side` (horizontal).
  void wall(const std::string& group, const std::string& material, glm::dvec2 a, glm::dvec2 b, double z0,
            double z1, glm::dvec2 side) {
    face(group, material, {{a, z0}, {b, z0}, {b, z1}, {a, z1}}, {side, 0.0}, material != "opening");
  }

  void flat(const std::string& group, const std::string& material, const Loop2& loop, double z, bool up) {
    std::vector<model::Vec3> v;
    for (const glm::dvec2& p : loop) v.emplace_back(p, z);
    face(group, material, std::move(v), {0.0, 0.0, up ? 1.0 : -1.0});
  }

 private:
  Building& b_;
  std::map<std::pair<std::string, std::string>, std::size_t> index_;
};

}  // namespace walk::gen
