#pragma once
// The models the ray-casting tests and `walk bench rays` run on, by name, each through the project's own
// importer: the two EnergyPlus DXFs (read_dxf), the Quake levels (read_map), the OBJ meshes (read_mesh via
// assimp: conference room, Sibenik, Cornell box), and the generated office tower.
#include <string>
#include <vector>

#include "bench/support/office_tower.hpp"
#include "compiler/geometry/mesher.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "compiler/import/map_reader.hpp"
#include "compiler/import/mesh_reader.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/error.hpp"

namespace walk::bench {

struct RayModel {
  std::string name;
  std::vector<compiler::Triangle> triangles;
  std::size_t polygons = 0;
};

inline const std::vector<std::string>& ray_model_names() {
  static const std::vector<std::string> names{"house", "office",     "tower",   "e1m1",
                                              "dm1",   "conference", "sibenik", "cornell"};
  return names;
}

// Polygons fanned into triangles (DXF 3DFACEs are convex triangles and quads).
inline std::vector<compiler::Triangle> fan_polygons(const model::Model& m) {
  std::vector<compiler::Triangle> out;
  for (std::uint32_t p = 0; p < m.polygons.size(); ++p) {
    const auto& v = m.polygons[p].vertices;
    for (std::size_t j = 1; j + 1 < v.size(); ++j) out.push_back({v[0], v[j], v[j + 1], p});
  }
  return out;
}

// The surfaces a ray can meet (not openings, not ignored faces), triangulated by the pipeline's mesher
// (brush faces after CSG may be non-convex).
inline std::vector<compiler::Triangle> mesh_polygons(const model::Model& m) {
  std::vector<compiler::Triangle> out;
  for (std::uint32_t p = 0; p < m.polygons.size(); ++p) {
    const auto& poly = m.polygons[p];
    if (poly.role == model::Role::Opening || poly.role == model::Role::Ignored) continue;
    const auto mesh = compiler::mesh_polygon(poly, 0.0);
    for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3)
      out.push_back({mesh.vertices[mesh.triangles[i]], mesh.vertices[mesh.triangles[i + 1]],
                     mesh.vertices[mesh.triangles[i + 2]], p});
  }
  return out;
}

inline std::vector<compiler::Triangle> read_obj(const std::string& path, double scale,
                                                std::size_t* polygons) {
  compiler::MeshOptions options;
  options.unit_scale = scale;
  options.y_up = true;
  const model::Model m = compiler::read_mesh(path, options, nullptr);
  *polygons = m.polygons.size();
  return fan_polygons(m);  // assimp faces are triangles and convex polygons
}

// `data` is the shared data folder (WALK_SHARED_DATA). Throws walk::Error for an unknown name.
inline RayModel load_ray_model(const std::string& name, const std::string& data) {
  RayModel r{name, {}, 0};
  if (name == "house" || name == "office") {
    const std::string path = name == "house" ? data + "/eplus-house-doors/house.dxf"
                                             : data + "/eplus-medium-office/refbldg_medium_office.dxf";
    const model::Model m = compiler::read_dxf(path);
    r.triangles = fan_polygons(m);
    r.polygons = m.polygons.size();
  } else if (name == "tower") {
    r.triangles = office_tower({}, &r.polygons);
  } else if (name == "e1m1" || name == "dm1") {
    const model::Model m = compiler::read_map(data + "/quake-maps/" + name + ".map");
    r.triangles = mesh_polygons(m);
    r.polygons = m.polygons.size();
  } else if (name == "conference") {
    r.triangles = read_obj(data + "/conference-room/conference.obj", 0.003, &r.polygons);
  } else if (name == "sibenik") {
    r.triangles = read_obj(data + "/sibenik/sibenik.obj", 1.0, &r.polygons);
  } else if (name == "cornell") {
    r.triangles = read_obj(data + "/cornell-box/CornellBox-Original.obj", 1.0, &r.polygons);
  } else {
    throw Error("unknown ray model '" + name +
                "' (house, office, tower, e1m1, dm1, conference, sibenik, cornell)");
  }
  return r;
}

}  // namespace walk::bench
