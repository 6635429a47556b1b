#include "test_bundle.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "model/model.hpp"

namespace walk::kiosk::testing {
namespace {

void add_quad(model::BundleContents& b, glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 p2, glm::dvec3 p3,
              model::Role role, std::uint32_t group) {
  const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  model::PolygonRecord poly{};
  poly.first_index = static_cast<std::uint32_t>(b.indices.size());
  poly.index_count = 6;
  poly.first_vertex = static_cast<std::uint32_t>(b.vertices.size());
  poly.vertex_count = 4;
  poly.material = 0;
  poly.group = group;
  poly.role = static_cast<std::uint32_t>(role);
  const auto id = static_cast<std::uint32_t>(b.polygons.size());
  for (const auto& p : {p0, p1, p2, p3}) {
    model::VertexRecord v{};
    for (int k = 0; k < 3; ++k) {
      v.position[k] = static_cast<float>(p[k]);
      v.normal[k] = static_cast<float>(n[k]);
      v.albedo[k] = 0.5f;
    }
    v.polygon = id;
    b.vertices.push_back(v);
  }
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) b.indices.push_back(poly.first_vertex + i);
  b.polygons.push_back(poly);
}

// A vertical wall rectangle in the plane through (x0,y0)-(x1,y1), from z0 to z1.
void add_wall(model::BundleContents& b, double x0, double y0, double x1, double y1, double z0, double z1,
              model::Role role = model::Role::Opaque, std::uint32_t group = 0) {
  add_quad(b, {x0, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y0, z1}, role, group);
}

// A horizontal rectangle; up = true faces +z.
void add_flat(model::BundleContents& b, double x0, double y0, double x1, double y1, double z, bool up,
              std::uint32_t group) {
  if (up)
    add_quad(b, {x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, model::Role::Opaque, group);
  else
    add_quad(b, {x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}, model::Role::Opaque, group);
}

}  // namespace

model::BundleContents two_room_contents() {
  using model::Role;
  model::BundleContents b;
  b.meta.origin[0] = 100.0;
  b.meta.origin[1] = 200.0;
  b.meta.origin[2] = 10.0;
  b.meta.exposure = 1.0f;
  b.meta.ambient = 0.2f;
  b.materials.push_back({{0.5f, 0.5f, 0.5f}, b.add_string("grey")});
  b.groups.push_back({b.add_string("A")});
  b.groups.push_back({b.add_string("B")});
  b.circuits.push_back({b.add_string("A"), 1.0f});
  b.circuits.push_back({b.add_string("B"), 0.5f});
  b.meta.circuit_count = 2;

  add_flat(b, 0, 0, 4, 4, 0.0, true, 0);       // floor A
  add_flat(b, 4, 0, 8, 4, 0.29, true, 1);      // floor B, one sill higher
  add_flat(b, 0, 0, 8, 4, 3.0, false, 0);      // ceiling
  add_wall(b, 0, 4, 0, 0, 0, 3, Role::Glass);  // x = 0, glass
  add_wall(b, 0, 0, 8, 0, 0, 3);               // y = 0
  add_wall(b, 8, 0, 8, 4, 0, 3);               // x = 8
  add_wall(b, 8, 4, 0, 4, 0, 3);               // y = 4
  // Partition x = 4 around the door hole y 1.5..2.5, z 0.29..2.1.
  add_wall(b, 4, 0, 4, 1.5, 0, 3);
  add_wall(b, 4, 2.5, 4, 4, 0, 3);
  add_wall(b, 4, 1.5, 4, 2.5, 0, 0.29);                   // sill
  add_wall(b, 4, 1.5, 4, 2.5, 2.1, 3);                    // lintel
  add_wall(b, 4, 1.5, 4, 2.5, 0.29, 2.1, Role::Opening);  // the door itself: a hole, never solid
  // Platform 0.5 m high in room A.
  add_flat(b, 1, 3, 2, 4, 0.5, true, 0);
  add_wall(b, 1, 3, 2, 3, 0, 0.5);
  add_wall(b, 1, 4, 1, 3, 0, 0.5);
  add_wall(b, 2, 3, 2, 4, 0, 0.5);

  for (int k = 0; k < 3; ++k) {
    b.meta.bounds_min[k] = 0.0f;
    b.meta.bounds_max[k] = k == 0 ? 8.0f : k == 1 ? 4.0f : 3.0f;
  }
  b.light = model::LightRows::from_dense(std::vector<float>(b.vertices.size() * b.circuits.size() * 3, 0.1f),
                                         b.circuits.size());
  // Two cells split at x = 4; every polygon potentially visible from both.
  model::CellRecord a{{0, 0, 0}, {4, 4, 3}, 0, 0}, c{{4, 0, 0}, {8, 4, 3}, 0, 0};
  for (std::uint32_t i = 0; i < b.polygons.size(); ++i) b.pvs.push_back(i);
  a.pvs_count = c.pvs_count = static_cast<std::uint32_t>(b.polygons.size());
  b.cells = {a, c};
  model::NodeRecord node{{1.0, 0.0, 0.0, -4.0}, -2, -1};  // x >= 4: cell 1 (B), else cell 0 (A)
  b.nodes = {node};
  return b;
}

std::string write_two_room_bundle(const std::string& path) {
  model::write_bundle(path, two_room_contents());
  return path;
}

}  // namespace walk::kiosk::testing
