#include "two_rooms.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>

#include "model/model.hpp"

namespace walk::render::test {
namespace {

struct Builder {
  const TwoRooms& scene;
  model::BundleContents c;
  std::uint32_t group_a = 0, group_b = 1;
  // [vertex][lit circuit][3] for the two lit circuits (the extra ones are dark), stored sparse in c.light
  // once every rectangle is in.
  std::vector<float> light;

  // A rectangle corner, corner+u, corner+u+v, corner+v: counter-clockwise about u x v, its front side.
  std::uint32_t rect(glm::dvec3 corner, glm::dvec3 u, glm::dvec3 v, bool room_b, double factor,
                     model::Role role = model::Role::Opaque) {
    const auto id = std::uint32_t(c.polygons.size());
    const glm::dvec3 albedo = room_b ? scene.albedo_b : scene.albedo_a;
    const glm::dvec3 n3 = glm::normalize(glm::cross(u, v));
    // An n x n grid of quads (n = scene.subdivisions): the same picture, more triangles for timing.
    const int n = std::max(1, scene.subdivisions);
    model::PolygonRecord p{};
    p.first_index = std::uint32_t(c.indices.size());
    p.index_count = std::uint32_t(6 * n * n);
    p.first_vertex = std::uint32_t(c.vertices.size());
    p.vertex_count = std::uint32_t((n + 1) * (n + 1));
    p.material = room_b ? 1 : 0;
    p.group = room_b ? group_b : group_a;
    p.role = std::uint32_t(role);
    c.polygons.push_back(p);
    const double* circuit = room_b ? scene.circuit_b : scene.circuit_a;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const glm::dvec3 q = corner + u * (double(i) / n) + v * (double(j) / n);
        model::VertexRecord vr{};
        for (int k = 0; k < 3; ++k) {
          vr.position[k] = float(q[k]);
          vr.normal[k] = float(n3[k]);
          vr.albedo[k] = float(albedo[k]);
        }
        vr.polygon = id;
        c.vertices.push_back(vr);
        const bool twisted = scene.light_twist || (scene.light_twist_half && 2 * i < n);
        const double gradient = scene.light_gradient ? 0.4 + 1.2 * double(i) / n
                                : twisted            ? ((i + j) % 2 == 0 ? 1.6 : 0.4)
                                                     : 1.0;
        for (int ci = 0; ci < std::min(scene.circuits, 2); ++ci)
          for (int k = 0; k < 3; ++k) light.push_back(float(albedo[k] * circuit[ci] * factor * gradient));
      }
    const std::uint32_t b = p.first_vertex, row = std::uint32_t(n + 1);
    for (std::uint32_t j = 0; j < std::uint32_t(n); ++j)
      for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
        const std::uint32_t q = b + j * row + i;
        for (std::uint32_t k : {q, q + 1, q + row + 1, q, q + row + 1, q + row}) c.indices.push_back(k);
      }
    if (scene.coarse_form) {
      const std::uint32_t top = b + std::uint32_t(n) * row;  // corners b, b + n, top + n, top
      c.coarse_ranges.push_back({std::uint32_t(c.coarse_indices.size()), 6});
      for (std::uint32_t k : {b, b + row - 1, top + row - 1, b, top + row - 1, top})
        c.coarse_indices.push_back(k);
    }
    return id;
  }

  // Walls at x = x0 and x = x0 + 4, floor, ceiling, side walls; the shared wall at x = 4 has the door.
  void room(double x0, bool room_b) {
    const double x1 = x0 + 4.0, f = scene.wall_factor;
    rect({x0, 0, 0}, {4, 0, 0}, {0, 4, 0}, room_b, scene.floor_factor);    // floor, +z
    rect({x0, 0, 3}, {0, 4, 0}, {4, 0, 0}, room_b, scene.ceiling_factor);  // ceiling, -z
    rect({x0, 0, 0}, {0, 0, 3}, {4, 0, 0}, room_b, f);                     // y = 0, +y
    rect({x0, 4, 0}, {4, 0, 0}, {0, 0, 3}, room_b, f);                     // y = 4, -y
    // Outer wall: A's at x = 0 faces +x, B's at x = 8 faces -x.
    if (!room_b)
      rect({x0, 0, 0}, {0, 4, 0}, {0, 0, 3}, false, f);
    else
      rect({x1, 0, 0}, {0, 0, 3}, {0, 4, 0}, true, f);
    // Shared wall at x = 4 around the opening: A's copy faces -x, B's faces +x.
    struct Piece {
      double y0, y1, z0, z1;
    };
    for (const Piece& s : {Piece{0, 1.5, 0, 3}, Piece{2.5, 4, 0, 3}, Piece{1.5, 2.5, 2.2, 3}}) {
      const glm::dvec3 dy{0, s.y1 - s.y0, 0}, dz{0, 0, s.z1 - s.z0}, corner{4, s.y0, s.z0};
      if (!room_b)
        rect(corner, dz, dy, false, f);
      else
        rect(corner, dy, dz, true, f);
    }
  }
};

}  // namespace

model::BundleContents make_two_rooms(const TwoRooms& scene) {
  Builder b{scene, {}, 0, 1, {}};
  auto& c = b.c;
  c.materials.push_back(
      {{float(scene.albedo_a.x), float(scene.albedo_a.y), float(scene.albedo_a.z)}, c.add_string("room_a")});
  c.materials.push_back(
      {{float(scene.albedo_b.x), float(scene.albedo_b.y), float(scene.albedo_b.z)}, c.add_string("room_b")});
  c.groups.push_back({c.add_string("A")});
  c.groups.push_back({c.add_string("B")});
  b.room(0.0, false);
  const auto room_a_end = std::uint32_t(c.polygons.size());
  // The door itself: never drawn. Drawn, it would cover the view into B in the middle of the picture.
  b.rect({4, 1.5, 0}, {0, 0, 2.2}, {0, 1, 0}, false, scene.wall_factor,
         scene.glass_door ? model::Role::Glass : model::Role::Opening);
  if (scene.crate) {
    const double f = scene.wall_factor;
    b.rect({4.5, 0.2, 0.5}, {0.5, 0, 0}, {0, 0.5, 0}, true, f);  // top, +z
    b.rect({4.5, 0.2, 0}, {0, 0, 0.5}, {0, 0.5, 0}, true, f);    // -x
    b.rect({5.0, 0.2, 0}, {0, 0.5, 0}, {0, 0, 0.5}, true, f);    // +x
    b.rect({4.5, 0.2, 0}, {0.5, 0, 0}, {0, 0, 0.5}, true, f);    // -y
    b.rect({4.5, 0.7, 0}, {0, 0, 0.5}, {0.5, 0, 0}, true, f);    // +y
  }
  b.room(4.0, true);
  const auto total = std::uint32_t(c.polygons.size());
  c.light = model::LightRows::from_dense(b.light, std::size_t(std::min(scene.circuits, 2)));

  for (int i = 0; i < scene.circuits; ++i)
    c.circuits.push_back({c.add_string("circuit" + std::to_string(i)), 1.0f});
  c.meta.ambient = scene.ambient;
  c.meta.exposure = scene.exposure;
  c.meta.circuit_count = std::uint32_t(scene.circuits);
  for (int k = 0; k < 3; ++k) {
    c.meta.bounds_min[k] = 0.0f;
    c.meta.bounds_max[k] = k == 0 ? 8.0f : k == 1 ? 4.0f : 3.0f;
  }
  if (scene.four_cells) {
    // Room A's shared-wall pieces are polygons 5..7, room B's the last three (see room()).
    auto pvs_without = [&](std::uint32_t first, std::uint32_t count) {
      const auto start = std::uint32_t(c.pvs.size());
      for (std::uint32_t i = 0; i < total; ++i)
        if (i < first || i >= first + count) c.pvs.push_back(i);
      return std::pair{start, std::uint32_t(c.pvs.size()) - start};
    };
    const auto [a_first, a_count] = pvs_without(total - 3, 3);
    const auto [b_first, b_count] = pvs_without(5, 3);
    c.nodes.push_back({{-1.0, 0.0, 0.0, 4.0}, 1, 2});  // front: x < 4, room A
    c.nodes.push_back({{0.0, -1.0, 0.0, 2.0}, -1, -2});
    c.nodes.push_back({{0.0, -1.0, 0.0, 2.0}, -3, -4});
    c.cells.push_back({{0, 0, 0}, {4, 2, 3}, a_first, a_count});
    c.cells.push_back({{0, 2, 0}, {4, 4, 3}, a_first, a_count});
    c.cells.push_back({{4, 0, 0}, {8, 2, 3}, b_first, b_count});
    c.cells.push_back({{4, 2, 0}, {8, 4, 3}, b_first, b_count});
    return c;
  }
  // Cell A: x < 4 (plane -x + 4 >= 0 is front), cell B: the rest.
  c.nodes.push_back({{-1.0, 0.0, 0.0, 4.0}, -1, -2});
  const std::uint32_t seen_from_a = scene.cell_a_sees_b ? total : room_a_end + 1;
  for (std::uint32_t i = 0; i < seen_from_a; ++i) c.pvs.push_back(i);
  for (std::uint32_t i = 0; i < total; ++i) c.pvs.push_back(i);
  c.cells.push_back({{0, 0, 0}, {4, 4, 3}, 0, seen_from_a});
  c.cells.push_back({{4, 0, 0}, {8, 4, 3}, seen_from_a, total});
  return c;
}

std::unique_ptr<model::Bundle> open_two_rooms(const TwoRooms& scene, const std::string& name) {
  return open_bundle(make_two_rooms(scene), name);
}

const std::filesystem::path& test_folder() {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("walk_render_tests_" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;  // a folder already gone is no failure at exit
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

std::unique_ptr<model::Bundle> open_bundle(const model::BundleContents& contents, const std::string& name) {
  const std::string path = (test_folder() / (name + ".walk")).string();
  model::write_bundle(path, contents);
  return model::Bundle::open(path);
}

int expected_byte(double radiosity, double exposure) {
  const double c = std::clamp(radiosity / exposure, 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return int(std::lround(encoded * 255.0));
}

glm::dvec3 radiosity(const TwoRooms& scene, bool room_b, double factor, double level0, double level1) {
  const glm::dvec3 albedo = room_b ? scene.albedo_b : scene.albedo_a;
  const double* circuit = room_b ? scene.circuit_b : scene.circuit_a;
  return albedo * (double(scene.ambient) + factor * (level0 * circuit[0] + level1 * circuit[1]));
}

}  // namespace walk::render::test
