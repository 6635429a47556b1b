#pragma once
// The models the ray-casting tests and `walk bench rays` run on, by name, each through the project's own
// importer: the two EnergyPlus DXFs (read_dxf), the Quake levels (read_map), the OBJ meshes (read_mesh via
// assimp: conference room, Sibenik, Cornell box), and the generated office tower; and, as "NAME@G", a model's
// surfaces diced into the radiosity patches that the solver casts its rays against.
#include <charconv>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "compiler/cleanup/cleanup.hpp"
#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/t_junctions.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "compiler/import/map_reader.hpp"
#include "compiler/import/mesh_reader.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/error.hpp"
#include "tools/bench_support/office_tower.hpp"

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

// A surface a ray can meet: not an opening, not an ignored face.
inline bool meets_rays(const model::Polygon& poly) {
  return poly.role != model::Role::Opening && poly.role != model::Role::Ignored;
}

inline void append_triangles(std::vector<compiler::Triangle>& out, const compiler::PolygonMesh& mesh,
                             std::uint32_t polygon) {
  for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3)
    out.push_back({mesh.vertices[mesh.triangles[i]], mesh.vertices[mesh.triangles[i + 1]],
                   mesh.vertices[mesh.triangles[i + 2]], polygon});
}

// The surfaces a ray can meet, triangulated by the pipeline's mesher (brush faces after CSG may be
// non-convex).
inline std::vector<compiler::Triangle> mesh_polygons(const model::Model& m) {
  std::vector<compiler::Triangle> out;
  for (std::uint32_t p = 0; p < m.polygons.size(); ++p)
    if (meets_rays(m.polygons[p])) append_triangles(out, compiler::mesh_polygon(m.polygons[p], 0.0), p);
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

// The surfaces a ray can meet diced on a `grid`-metre grid and their seams repaired, as the display
// compiler's mesh stage makes the radiosity patches that the solver casts its rays against (without the
// clean-up stage before it). On a 1 m grid a Quake level has 4 times as many triangles as undiced.
inline std::vector<compiler::Triangle> diced_polygons(const model::Model& m, double grid) {
  std::vector<compiler::PolygonMesh> meshes;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t p = 0; p < m.polygons.size(); ++p)
    if (meets_rays(m.polygons[p])) {
      meshes.push_back(compiler::mesh_polygon(m.polygons[p], grid));
      ids.push_back(p);
    }
  compiler::repair_t_junctions(meshes, compiler::kWeldRelative * glm::length(model::bounds_of(m).size()));
  std::vector<compiler::Triangle> out;
  for (std::size_t i = 0; i < meshes.size(); ++i) append_triangles(out, meshes[i], ids[i]);
  return out;
}

// The polygons of a model read from files (the tower is generated as triangles and has none).
inline model::Model read_ray_model_polygons(const std::string& name, const std::string& data) {
  if (name == "house") return compiler::read_dxf(data + "/eplus-house-doors/house.dxf");
  if (name == "office") return compiler::read_dxf(data + "/eplus-medium-office/refbldg_medium_office.dxf");
  if (name == "e1m1" || name == "dm1") return compiler::read_map(data + "/quake-maps/" + name + ".map");
  throw Error("ray model '" + name + "' has no polygons to dice (house, office, e1m1, dm1 have)");
}

// `data` is the shared data folder (WALK_SHARED_DATA). Throws walk::Error for an unknown name.
// "NAME@G" (house, office, e1m1, dm1): that model's patches on a G-metre grid (diced_polygons).
inline RayModel load_ray_model(const std::string& name, const std::string& data) {
  RayModel r{name, {}, 0};
  if (const auto at = name.find('@'); at != std::string::npos) {
    double grid = 0.0;
    const char* first = name.data() + at + 1;
    const char* last = name.data() + name.size();
    const auto [end, ec] = std::from_chars(first, last, grid);
    if (ec != std::errc() || end != last || !(grid > 0.0) || !std::isfinite(grid))
      throw Error("ray model '" + name + "': the grid after '@' must be a positive number of metres");
    const model::Model m = read_ray_model_polygons(name.substr(0, at), data);
    r.triangles = diced_polygons(m, grid);
    r.polygons = m.polygons.size();
    return r;
  }
  if (name == "house" || name == "office") {
    const model::Model m = read_ray_model_polygons(name, data);
    r.triangles = fan_polygons(m);
    r.polygons = m.polygons.size();
  } else if (name == "tower") {
    r.triangles = office_tower({}, &r.polygons);
  } else if (name == "e1m1" || name == "dm1") {
    const model::Model m = read_ray_model_polygons(name, data);
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
                "' (house, office, tower, e1m1, dm1, conference, sibenik, cornell, or NAME@G)");
  }
  return r;
}

}  // namespace walk::bench
