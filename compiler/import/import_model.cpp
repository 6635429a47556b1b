#include "compiler/import/import_model.hpp"

#include <fmt/format.h>

#include <fstream>

#include "compiler/import/dxf_reader.hpp"
#include "compiler/import/map_reader.hpp"
#include "compiler/import/mesh_reader.hpp"
#include "compiler/import/plan_builder.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

std::string counts(const std::map<std::string, std::size_t>& m) {
  std::string out;
  for (const auto& [k, v] : m) out += (out.empty() ? "" : " ") + k + " " + std::to_string(v);
  return out.empty() ? "none" : out;
}

model::Model import_dxf(const SceneConfig& config, bool plan, std::string& detail) {
  std::ifstream in(config.model_file, std::ios::binary);
  if (!in)
    throw Error(located(config.model_file, 0, "cannot open the DXF file",
                        "check the path in the scene config and that the file exists and is readable"));
  DxfStats s;
  std::vector<DxfWire> wires;
  model::Model m = read_dxf(in, config.model_file, {config.metres_per_unit, !config.units_given}, &s,
                            plan ? &wires : nullptr);
  detail = fmt::format(
      "read [{}] skipped [{}] faces {} degenerate {} wires {} blocks placed {} (mirrored {}) "
      "true-colour faces {} unit {} m{}",
      counts(s.read), counts(s.skipped), s.faces, s.degenerate, s.wires, s.block_instances,
      s.mirrored_instances, s.true_colours, s.unit_scale,
      s.insunits ? fmt::format(" ($INSUNITS {})", *s.insunits) : std::string());
  if (!plan) return m;
  // Window positions are in drawing units, converted with the config's unit; when the file's $INSUNITS
  // chose the unit instead, convert them with that.
  PlanOptions options = config.plan;
  for (auto& w : options.windows) w.at *= s.unit_scale / config.metres_per_unit;
  PlanStats ps;
  model::Model built = build_plan(wires, options, config.model_file, &ps);
  detail += fmt::format(
      "; plan: outlines {} open wires {} jambs {} doorways {} rooms {} windows {} (unplaced {}) "
      "wall footprint {:.2f} m2 floor {:.2f} m2",
      ps.loops, ps.open_wires, ps.jambs, ps.doorways, ps.rooms, ps.windows, ps.windows_unplaced, ps.wall_area,
      ps.floor_area);
  // Surfaces the plan also had (3DFACE, thick lines) come along.
  for (auto& p : m.polygons) {
    p.group = built.group_index(m.groups[p.group]);
    built.polygons.push_back(std::move(p));
  }
  built.materials = std::move(m.materials);
  return built;
}

}  // namespace

model::Model import_model(const SceneConfig& config, ImportReport* report) {
  ImportReport r;
  r.format = config.format;
  model::Model m;
  if (config.format == "dxf" || config.format == "plan") {
    m = import_dxf(config, config.format == "plan", r.detail);
  } else if (config.format == "map") {
    MapStats s;
    m = read_map(config.model_file, {config.metres_per_unit}, &s);
    r.detail = fmt::format(
        "entities {} brushes {} ({} planes, {}) built {} clip {} trigger {} door {} | degenerate planes {} "
        "duplicate "
        "{} open {} empty {} slivers {} welded corners {} | csg faces {} hidden {} split {} -> {} | sky {} "
        "liquid {} "
        "lights {} (spot {})",
        s.entities, s.brushes, s.brush_planes, s.valve220 ? "Valve 220" : "standard", s.brushes_built,
        s.clip_brushes, s.trigger_brushes, s.door_brushes, s.brush.degenerate_planes,
        s.brush.duplicate_planes, s.brush.open_brushes, s.brush.empty_brushes, s.brush.sliver_faces,
        s.brush.welded_corners, s.csg.faces_in, s.csg.faces_hidden, s.csg.faces_split, s.csg.fragments_out,
        s.sky_faces, s.liquid_faces, s.lights, s.spot_lights);
  } else {
    MeshStats s;
    m = read_mesh(config.model_file, {config.metres_per_unit, config.y_up, 1.0, config.texture_dirs}, &s);
    r.detail = fmt::format(
        "meshes {} vertices {} faces {} (triangles {}) points/lines skipped {} materials {} "
        "emissive faces {} -> luminaires {} textures named {} loaded {} missing {} textured faces {} "
        "material libraries missing {}",
        s.meshes, s.vertices, s.faces, s.triangles, s.skipped_primitives, s.materials, s.emissive_faces,
        s.luminaires, s.textures_named, s.textures_loaded, s.textures_missing, s.faces_textured,
        s.material_libraries_missing);
  }
  // Imported materials go after the config's (index 0, "default", is the config's default).
  const auto first = static_cast<std::uint32_t>(config.materials.empty() ? 1 : config.materials.size());
  for (std::size_t i = 1; i < m.materials.size(); ++i) r.materials.push_back(m.materials[i]);
  for (auto& p : m.polygons)
    if (p.material > 0) p.material = first + p.material - 1;
  m.materials = config.materials.empty() ? std::vector<model::Material>{{"default", {0.5, 0.5, 0.5}}}
                                         : config.materials;
  m.materials.insert(m.materials.end(), r.materials.begin(), r.materials.end());
  r.faces = m.polygons.size();
  for (const auto& p : m.polygons) r.openings += p.role == model::Role::Opening ? 1 : 0;
  r.luminaires = m.luminaires.size();
  r.circuits = m.circuits.size();
  if (report) *report = std::move(r);
  return m;
}

void append_imported_materials(model::Model& model, const SceneConfig& config, const ImportReport& report) {
  if (model.materials.size() != std::max<std::size_t>(1, config.materials.size())) return;
  model.materials.insert(model.materials.end(), report.materials.begin(), report.materials.end());
}

}  // namespace walk::compiler
