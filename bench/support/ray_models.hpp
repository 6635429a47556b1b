#pragma once
// The models the ray-casting tests and `walk bench rays` run on, by name: the two EnergyPlus DXFs through
// the real importer, the generated office tower, and the OBJ meshes (conference room, Sibenik, Cornell box).
#include <string>
#include <vector>

#include "bench/support/obj_triangles.hpp"
#include "bench/support/office_tower.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "compiler/raycast/triangle_bvh.hpp"

namespace walk::bench {

struct RayModel {
  std::string name;
  std::vector<compiler::Triangle> triangles;
  std::size_t polygons = 0;
};

inline const std::vector<std::string>& ray_model_names() {
  static const std::vector<std::string> names{"house", "office", "tower", "conference", "sibenik", "cornell"};
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
  } else if (name == "conference") {
    r.triangles = read_obj_triangles(data + "/conference-room/conference.obj", 0.003, &r.polygons);
  } else if (name == "sibenik") {
    r.triangles = read_obj_triangles(data + "/sibenik/sibenik.obj", 1.0, &r.polygons);
  } else if (name == "cornell") {
    r.triangles = read_obj_triangles(data + "/cornell-box/CornellBox-Original.obj", 1.0, &r.polygons);
  } else {
    throw Error("unknown ray model '" + name + "' (house, office, tower, conference, sibenik, cornell)");
  }
  return r;
}

}  // namespace walk::bench
