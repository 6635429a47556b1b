#include "compiler/scene/scene_config.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <numbers>

#include "compiler/photometry/colour_temperature.hpp"
#include "compiler/photometry/photometry_file.hpp"
#include "compiler/raycast/ray_caster.hpp"
#include "compiler/scene/units.hpp"
#include "model/error.hpp"
#include "model/photometric_units.hpp"
#include "model/toml_table.hpp"

namespace walk::compiler {
namespace {

namespace fs = std::filesystem;

std::regex compile_regex(const TomlTable& t, const std::string& key) {
  const auto text = t.string(key);
  try {
    return std::regex(*text, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    t.fail(key, "not a valid regular expression: " + std::string(e.what()));
  }
}

model::Rgb rgb01(const TomlTable& t, const std::string& key, model::Rgb fallback) {
  const auto v = t.numbers(key, 3);
  if (!v) return fallback;
  for (double c : *v)
    if (!(c >= 0.0 && c <= 1.0)) t.fail(key, "each component must be between 0 and 1");
  return {(*v)[0], (*v)[1], (*v)[2]};
}

double positive(const TomlTable& t, const std::string& key, double fallback) {
  const auto v = t.number(key);
  if (!v) return fallback;
  if (!(*v > 0.0)) t.fail(key, "must be greater than 0");
  return *v;
}

// A light's colour: `colour` (RGB) or `cct` (kelvin), not both.
model::Rgb light_colour(const TomlTable& t, model::Rgb fallback) {
  if (t.has("colour") && t.has("cct")) t.fail("cct", "give `colour` or `cct`, not both");
  if (!t.has("cct")) {
    return rgb01(t, "colour", fallback);
  }
  const double k = t.number("cct", 0.0, kMinCct, kMaxCct);
  const model::Rgb c = cct_colour(k);
  return c / std::max({c.r, c.g, c.b});  // brightest channel 1, as an RGB `colour` is written
}

// A light's radiant power per unit of `colour`: `power` (W per channel) or `flux` (lumens), not both.
double light_power(const TomlTable& t, const model::Rgb& colour, double fallback_watts) {
  if (t.has("power") && t.has("flux")) t.fail("flux", "give `power` (W) or `flux` (lm), not both");
  if (!t.has("flux")) return positive(t, "power", fallback_watts);
  if (!(model::luminance_weight(colour) > 0.0))
    t.fail("colour", "must not be black when `flux` gives the lumens");
  return positive(t, "flux", 1.0) / (model::kLumensPerWatt * model::luminance_weight(colour));
}

// A direction given as [x, y, z]: not zero, returned unit length.
model::Vec3 unit_vector(const TomlTable& t, const std::string& key, model::Vec3 fallback) {
  model::Vec3 v = fallback;
  if (const auto n = t.numbers(key, 3)) v = {(*n)[0], (*n)[1], (*n)[2]};
  if (!(glm::dot(v, v) > 1e-12) || !std::isfinite(glm::dot(v, v)))
    t.fail(key, "must be a finite, non-zero direction");
  return glm::normalize(v);
}

// The solver's estimate is a Poisson error over ray hits: below 0.1 % the rays needed pass any budget, and
// above 50 % the light is noise.
constexpr double kMinTargetError = 0.001;
constexpr double kMaxTargetError = 0.5;

// |cos| between a fixture's aim and its C0 direction beyond which C0 is undefined (about 2.6 degrees).
constexpr double kAlongAim = 0.999;

// Formats import_model reads: DXF (3D), a 2D DXF plan, Quake .map, and meshes through assimp.
constexpr const char* kFormats[] = {"dxf", "plan", "map", "obj", "gltf", "glb",
                                    "3ds", "ply",  "dae", "fbx", "stl",  "off"};

void read_model(const TomlTable& root, SceneConfig& cfg) {
  const auto model = root.table("model");
  if (!model) root.fail("model", "missing [model] table with at least `file = \"building.dxf\"`");
  model->only({"file", "format", "units", "scale", "up", "faces", "weld", "seal", "textures", "outliers"});
  if (model->has("weld")) {
    cfg.weld_metres = positive(*model, "weld", 0.0);
    if (cfg.weld_metres > 0.01)
      model->fail("weld", "at most 0.01 (metres): a weld that large merges real corners, not printing noise");
  }
  if (model->has("seal")) {
    cfg.seal_metres = positive(*model, "seal", 0.0);
    if (cfg.seal_metres > 0.1)
      model->fail("seal", "at most 0.1 (metres): wider gaps are real openings, not modelling slits");
  }
  const auto file = model->string("file");
  if (!file) model->fail("file", "missing: name the building model to import");
  fs::path p(*file);
  if (p.is_relative()) p = fs::path(cfg.path).parent_path() / p;
  cfg.model_file = p.lexically_normal().string();
  std::error_code folder_error;
  if (fs::is_directory(p, folder_error))
    model->fail("file", "'" + cfg.model_file + "' is a folder; name the model file inside it");
  std::string ext = p.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  cfg.format = model->string("format").value_or(ext.empty() ? "" : ext.substr(1));
  if (std::find(std::begin(kFormats), std::end(kFormats), cfg.format) == std::end(kFormats))
    model->fail("format",
                "format '" + cfg.format +
                    "' is not supported (supported: dxf, plan, map, obj, gltf, glb, 3ds, ply, dae, fbx, "
                    "stl, off)");
  const std::string units = model->string("units").value_or(cfg.format == "map" ? "quake" : "m");
  const auto scale = metres_per_unit(units);
  if (!scale) model->fail("units", "unknown unit '" + units + "' (known: " + known_units() + ")");
  cfg.metres_per_unit = *scale;
  cfg.units_given = model->has("units");
  if (model->has("scale")) {
    if (cfg.units_given)
      model->fail("scale", "give either `units` or `scale` (metres per model unit), not both");
    cfg.metres_per_unit = positive(*model, "scale", 1.0);
    cfg.units_given = true;
  }
  const bool mesh = cfg.format != "dxf" && cfg.format != "plan" && cfg.format != "map";
  const std::string up = model->string("up").value_or(mesh ? "y" : "z");
  if (up != "y" && up != "z") model->fail("up", "must be \"y\" or \"z\" (the file's up axis)");
  cfg.y_up = up == "y";
  const std::string faces = model->string("faces").value_or("inward");
  if (faces != "inward" && faces != "outward")
    model->fail("faces", "must be \"inward\" (faces look into their room) or \"outward\" (EnergyPlus zones)");
  cfg.faces_point_outward = faces == "outward";
  const std::string outliers = model->string("outliers").value_or("drop");
  if (outliers != "drop" && outliers != "keep")
    model->fail("outliers",
                "must be \"drop\" (faces far from the rest are left out, the default) or \"keep\"");
  cfg.keep_outliers = outliers == "keep";
  // Folders searched for albedo maps after the model's own, relative to the config like `file`.
  if (model->has("textures")) {
    const auto folders = model->strings("textures");
    if (!folders) model->fail("textures", "must be an array of folder names, e.g. [\"textures\"]");
    for (const auto& f : *folders) {
      fs::path d(f);
      if (d.is_relative()) d = fs::path(cfg.path).parent_path() / d;
      std::error_code ec;
      if (!fs::is_directory(d, ec))
        model->fail("textures", "'" + f + "' is not a folder (resolved to " + d.string() +
                                    "); name folders that hold the model's texture images");
      cfg.texture_dirs.push_back(d.lexically_normal().string());
    }
  }
}

void read_plan(const TomlTable& root, SceneConfig& cfg) {
  const auto t = root.table("plan");
  if (!t) return;
  if (cfg.format != "plan") t->fail("wall_height", "[plan] applies only to format = \"plan\"");
  t->only({"wall_height", "door_height", "door_width", "max_wall_thickness", "min_room_area", "windows"});
  auto& o = cfg.plan;
  o.wall_height = positive(*t, "wall_height", o.wall_height);
  o.door_height = positive(*t, "door_height", o.door_height);
  if (o.door_height > o.wall_height) t->fail("door_height", "must not exceed wall_height");
  if (const auto w = t->numbers("door_width", 2)) {
    o.min_door_width = (*w)[0];
    o.max_door_width = (*w)[1];
    if (!(o.min_door_width >= 0.0 && o.max_door_width > o.min_door_width))
      t->fail("door_width", "give [narrowest, widest] doorway in metres, 0 <= narrowest < widest");
  }
  o.max_wall_thickness = positive(*t, "max_wall_thickness", o.max_wall_thickness);
  o.min_room_area = positive(*t, "min_room_area", o.min_room_area);
  for (const auto& w : t->array_of_tables("windows")) {
    w.only({"at", "width", "sill", "head"});
    PlanWindow win;
    const auto at = w.numbers("at", 2);
    if (!at) w.fail("at", "missing: give [x, y] in model units, on or next to the wall");
    win.at = model::Vec3((*at)[0], (*at)[1], 0.0) * cfg.metres_per_unit;
    win.width = positive(w, "width", win.width);
    win.sill = w.number("sill").value_or(win.sill);
    win.head = positive(w, "head", win.head);
    if (!(win.sill >= 0.0 && win.head > win.sill && win.head <= o.wall_height))
      w.fail("head", "need 0 <= sill < head <= wall_height (metres)");
    o.windows.push_back(win);
  }
}

void read_rules(const TomlTable& root, SceneConfig& cfg) {
  for (const auto& t : root.array_of_tables("rules")) {
    t.only({"layer", "name", "color", "role", "material"});
    FaceRule rule;
    rule.where = t.where("role");
    if (t.has("layer")) rule.layer = compile_regex(t, "layer");
    if (t.has("name")) rule.name = compile_regex(t, "name");
    if (const auto c = t.integer("color")) rule.color = static_cast<int>(*c);
    if (const auto r = t.string("role")) {
      model::Role role;
      if (!model::parse_role(*r, role))
        t.fail("role", "unknown role '" + *r + "' (known: opaque, glass, opening, luminaire, ignored)");
      rule.role = role;
    }
    rule.material = t.string("material");
    if (!rule.role && !rule.material) t.fail("role", "a rule needs a role, a material or both");
    cfg.rules.push_back(std::move(rule));
  }
}

void read_materials(const TomlTable& root, SceneConfig& cfg) {
  cfg.materials.push_back({"default", {0.5, 0.5, 0.5}});
  const auto mats = root.table("materials");
  for (const auto& [key, node] : mats ? mats->raw() : toml::table{}) {
    const std::string name(key.str());
    const auto t = mats->table(name);
    t->only({"reflectance"});
    if (!t->has("reflectance")) t->fail("reflectance", "missing: give [r, g, b] between 0 and 1");
    model::Material m{name, rgb01(*t, "reflectance", {})};
    if (name == "default")
      cfg.materials[0] = m;
    else
      cfg.materials.push_back(m);
  }
  for (const auto& rule : cfg.rules) {
    if (!rule.material) continue;
    bool found = false;
    for (const auto& m : cfg.materials) found = found || m.name == *rule.material;
    if (!found)
      throw Error(rule.where + ": rule names material '" + *rule.material + "' that no [materials." +
                  *rule.material + "] table defines");
  }
}

// A panel's width runs along x projected into its plane, or along y when the panel faces along x: any
// normal gives a flat rectangle facing it (x alone made a panel facing along x collapse to a line).
model::Vec3 panel_width_axis(const model::Vec3& normal) {
  constexpr double kFacesAlongX = 0.999;  // |cos| of the angle between normal and x beyond which y is used
  const model::Vec3 along = std::abs(normal.x) > kFacesAlongX ? model::Vec3(0, 1, 0) : model::Vec3(1, 0, 0);
  return glm::normalize(along - glm::dot(along, normal) * normal);
}

void read_luminaires(const TomlTable& root, SceneConfig& cfg) {
  const auto lum = root.table("luminaires");
  if (!lum) return;
  lum->only({"per_group", "panel", "fixture"});
  if (const auto pg = lum->table("per_group")) {
    pg->only({"enabled", "size", "power", "flux", "colour", "cct", "drop", "exclude_groups"});
    auto& p = cfg.panels;
    p.enabled = pg->boolean("enabled").value_or(true);
    if (const auto size = pg->numbers("size", 2)) {
      p.width = (*size)[0];
      p.height = (*size)[1];
      if (!(p.width > 0 && p.height > 0)) pg->fail("size", "both sides must be greater than 0");
    }
    p.colour = light_colour(*pg, p.colour);
    p.power = light_power(*pg, p.colour, p.power);
    p.drop = pg->number("drop").value_or(p.drop);
    if (!(p.drop >= 0))
      pg->fail("drop", "must be 0 or more (metres below the ceiling; less puts the panel above it)");
    if (pg->has("exclude_groups")) p.exclude_groups = compile_regex(*pg, "exclude_groups");
  }
  for (const auto& t : lum->array_of_tables("panel")) {
    t.only({"name", "position", "normal", "size", "power", "flux", "colour", "cct", "circuit"});
    model::Luminaire l;
    l.name = t.string("name").value_or("panel" + std::to_string(cfg.luminaires.size()));
    const auto pos = t.numbers("position", 3);
    if (!pos) t.fail("position", "missing: give [x, y, z] in model units");
    l.position = model::Vec3((*pos)[0], (*pos)[1], (*pos)[2]) * cfg.metres_per_unit;
    if (const auto n = t.numbers("normal", 3)) l.normal = {(*n)[0], (*n)[1], (*n)[2]};
    if (glm::dot(l.normal, l.normal) < 1e-12) t.fail("normal", "must not be zero");
    l.normal = glm::normalize(l.normal);
    l.u_axis = panel_width_axis(l.normal);
    if (const auto size = t.numbers("size", 2)) {
      l.width = (*size)[0];
      l.height = (*size)[1];
      if (!(l.width > 0 && l.height > 0)) t.fail("size", "both sides must be greater than 0");
    }
    const model::Rgb colour = light_colour(t, {1, 1, 1});
    l.power = colour * light_power(t, colour, 60.0);
    cfg.luminaires.push_back(l);
    cfg.luminaire_circuits.push_back(t.string("circuit").value_or(l.name));
  }
  std::map<std::string, std::shared_ptr<const model::IntensityDistribution>> files;  // each read once
  for (const auto& t : lum->array_of_tables("fixture")) {
    t.only({"name", "position", "aim", "c0", "photometry", "flux", "colour", "cct", "circuit"});
    model::Luminaire l;
    l.kind = model::LuminaireKind::Photometric;
    l.name = t.string("name").value_or("fixture" + std::to_string(cfg.luminaires.size()));
    const auto pos = t.numbers("position", 3);
    if (!pos) t.fail("position", "missing: give [x, y, z] in model units");
    l.position = model::Vec3((*pos)[0], (*pos)[1], (*pos)[2]) * cfg.metres_per_unit;
    l.normal = unit_vector(t, "aim", {0, 0, -1});
    l.u_axis = t.has("c0") ? unit_vector(t, "c0", {1, 0, 0}) : panel_width_axis(l.normal);
    if (std::abs(glm::dot(l.u_axis, l.normal)) > kAlongAim)
      t.fail("c0", "must not lie along `aim`: it is the direction of the luminaire's C0 plane");
    const auto file = t.string("photometry");
    if (!file) t.fail("photometry", "missing: name the luminaire's IES (.ies) or EULUMDAT (.ldt) file");
    fs::path p(*file);
    if (p.is_relative()) p = fs::path(cfg.path).parent_path() / p;
    const std::string path = p.lexically_normal().string();
    auto& d = files[path];
    if (!d) {
      try {
        d = std::make_shared<const model::IntensityDistribution>(read_photometry_file(path));
      } catch (const Error& e) {
        t.fail("photometry", e.what());
      }
    }
    l.distribution = d;
    const model::Rgb colour = light_colour(t, {1, 1, 1});
    // The file's flux unless the scene gives the lamp's: a table is a shape, `flux` its scale.
    const double lumens = t.has("flux") ? positive(t, "flux", 1.0) : d->lumens;
    l.power = model::power_from_lumens(lumens, colour);
    cfg.luminaires.push_back(l);
    cfg.luminaire_circuits.push_back(t.string("circuit").value_or(l.name));
  }
}

void read_circuits(const TomlTable& root, SceneConfig& cfg) {
  for (const auto& t : root.array_of_tables("circuits")) {
    t.only({"name", "luminaires", "default_level"});
    CircuitRule c;
    const auto name = t.string("name");
    if (!name || name->empty()) t.fail("name", "missing: every circuit needs a name");
    c.name = *name;
    if (!t.has("luminaires")) t.fail("luminaires", "missing: a regular expression over luminaire names");
    c.luminaires = compile_regex(t, "luminaires");
    c.default_level = t.number("default_level").value_or(1.0);
    if (!(c.default_level >= 0.0 && c.default_level <= 1.0))
      t.fail("default_level", "must be between 0 and 1");
    cfg.circuits.push_back(std::move(c));
  }
}

// `[table] ray_caster`, when given, into `caster`: one of this build's casters. Plain Embree breaks the
// self-hit policy (ray_caster.hpp): a scene that picks it for its rays is told so, and compiles all the same.
void read_ray_caster(const TomlTable& t, const SceneConfig& cfg, const char* table, std::string& caster) {
  const auto name = t.string("ray_caster");
  if (!name) return;
  const auto names = ray_caster_names();
  if (std::find(names.begin(), names.end(), *name) == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    t.fail("ray_caster", "unknown ray caster '" + *name + "' (this build has: " + known + ")");
  }
  caster = *name;
  if (caster == "embree")
    spdlog::warn(
        "{}: [{}] ray_caster = \"embree\": plain Embree meets the surface a ray leaves (its float origin "
        "lies micrometres off it), so light is lost to back faces and the PVS grows; \"embree-exact\" "
        "keeps the self-hit policy",
        cfg.path, table);
}

void read_lighting(const TomlTable& root, SceneConfig& cfg) {
  const auto t = root.table("lighting");
  if (!t) return;
  t->only({"method", "grid", "samples_per_luminaire", "rays_per_watt", "residual", "ambient", "exposure",
           "white_luminance", "ray_caster", "target_error", "direct", "refine", "indirect"});
  auto& l = cfg.lighting;
  if (const auto m = t->string("method")) {
    if (*m == "radiosity")
      l.method = LightingMethod::Radiosity;
    else if (*m == "direct")
      l.method = LightingMethod::Direct;
    else
      t->fail("method", "unknown method '" + *m + "' (known: radiosity, direct)");
  }
  if (const auto d = t->string("direct")) {
    if (*d != "gather" && *d != "shoot") t->fail("direct", "unknown way '" + *d + "' (known: gather, shoot)");
    l.gather_direct = *d == "gather";
  }
  l.refine = t->boolean("refine").value_or(l.refine);
  if (const auto d = t->string("indirect")) {
    if (*d != "gather" && *d != "patches")
      t->fail("indirect", "unknown way '" + *d + "' (known: gather, patches)");
    l.gather_indirect = *d == "gather";
    if (l.gather_indirect && !l.gather_direct)
      t->fail("indirect", "'gather' needs direct light gathered too: add direct = \"gather\"");
  }
  l.grid = positive(*t, "grid", l.grid);
  if (l.grid < kMinGrid) t->fail("grid", "must be at least " + std::to_string(kMinGrid) + " m");
  if (const auto s = t->integer("samples_per_luminaire")) {
    if (*s < 1 || *s > 4096) t->fail("samples_per_luminaire", "must be between 1 and 4096");
    l.samples_per_luminaire = static_cast<int>(*s);
  }
  l.rays_per_watt = positive(*t, "rays_per_watt", l.rays_per_watt);
  if (t->has("target_error")) {
    if (t->has("rays_per_watt"))
      t->fail("target_error", "give `target_error` or the expert override `rays_per_watt`, not both");
    l.target_error = t->number("target_error", 0.0, kMinTargetError, kMaxTargetError);
  }
  l.residual = positive(*t, "residual", l.residual);
  if (l.residual >= 1.0) t->fail("residual", "must be below 1 (a fraction of the emitted power)");
  l.ambient = t->number("ambient").value_or(l.ambient);
  if (l.ambient < 0.0) t->fail("ambient", "must not be negative");
  read_ray_caster(*t, cfg, "lighting", l.ray_caster);
  if (t->has("exposure") && t->has("white_luminance"))
    t->fail("white_luminance", "give `exposure` (W/m2) or `white_luminance` (cd/m2), not both");
  if (t->has("exposure")) l.exposure = positive(*t, "exposure", 1.0);
  // A diffuse surface of radiosity B (W/m2 per channel, white) has luminance 179 B / pi cd/m2.
  if (t->has("white_luminance"))
    l.exposure = positive(*t, "white_luminance", 1.0) * std::numbers::pi / model::kLumensPerWatt;
}

void read_visibility(const TomlTable& root, SceneConfig& cfg) {
  const auto t = root.table("visibility");
  if (!t) return;
  t->only({"w_occlusion", "w_balance", "w_split", "threshold", "max_depth", "min_cell_size", "method",
           "sample_points", "rays_per_point", "flow_budget", "ray_caster", "cull_back_faces", "occluders",
           "proof_pairs", "detail_extent", "detail_area", "structure", "detail", "solids"});
  auto& v = cfg.visibility;
  v.cull_back_faces = t->boolean("cull_back_faces").value_or(v.cull_back_faces);
  v.occluders = t->boolean("occluders").value_or(v.occluders);
  v.use_solids = t->boolean("solids").value_or(v.use_solids);
  for (const auto& [key, field] :
       {std::pair{"w_occlusion", &v.w_occlusion}, std::pair{"w_balance", &v.w_balance},
        std::pair{"w_split", &v.w_split}, std::pair{"threshold", &v.threshold}}) {
    *field = t->number(key).value_or(*field);
    if (!(*field >= 0.0 && *field <= 1.0)) t->fail(key, "must be between 0 and 1");
  }
  if (const auto d = t->integer("max_depth")) {
    if (*d < 0 || *d > 64) t->fail("max_depth", "must be between 0 and 64");
    v.max_depth = static_cast<int>(*d);
  }
  v.min_cell_size = positive(*t, "min_cell_size", v.min_cell_size);
  if (const auto m = t->string("method"))
    if (!parse_pvs_method(*m, v.method))
      t->fail("method", "unknown method '" + *m + "' (known: sampled, conservative, combined)");
  if (const auto s = t->integer("sample_points")) {
    if (*s < 0 || *s > 1'000'000) t->fail("sample_points", "must be between 0 and 1000000");
    v.sample_points = static_cast<int>(*s);
  }
  if (const auto s = t->integer("rays_per_point")) {
    if (*s < 1 || *s > 1'000'000) t->fail("rays_per_point", "must be between 1 and 1000000");
    v.rays_per_point = static_cast<int>(*s);
  }
  if (const auto s = t->integer("proof_pairs")) {
    if (*s < 0 || *s > 1'000'000) t->fail("proof_pairs", "must be between 0 (no proofs) and 1000000");
    v.proof_pairs = static_cast<int>(*s);
  }
  if (const auto b = t->integer("flow_budget")) {
    if (*b < 1) t->fail("flow_budget", "must be at least 1");
    v.flow_budget = static_cast<std::uint64_t>(*b);
  }
  read_ray_caster(*t, cfg, "visibility", v.ray_caster);
  v.detail_extent = t->number("detail_extent").value_or(v.detail_extent);
  if (!(v.detail_extent >= 0.0)) t->fail("detail_extent", "must be 0 (no detail by size) or more, in metres");
  v.detail_area = t->number("detail_area").value_or(v.detail_area);
  if (!(v.detail_area >= 0.0))
    t->fail("detail_area", "must be 0 (no detail by area) or more, in square metres");
  if (t->has("structure")) v.structure_groups = compile_regex(*t, "structure");
  if (t->has("detail")) v.detail_groups = compile_regex(*t, "detail");
}

}  // namespace

void read_start(const TomlTable& root, SceneConfig& cfg) {
  const auto t = root.table("start");
  if (!t) return;
  t->only({"position", "heading_deg"});
  const auto pos = t->numbers("position", 3);
  if (!pos) t->fail("position", "missing: give [x, y, z] of a point on a floor, in model units");
  StartPoint s;
  s.position = model::Vec3((*pos)[0], (*pos)[1], (*pos)[2]) * cfg.metres_per_unit;
  s.heading = t->number("heading_deg").value_or(0.0) * std::numbers::pi / 180.0;
  if (!std::isfinite(s.heading) || !std::isfinite(s.position.x + s.position.y + s.position.z))
    t->fail("position", "must be finite");
  cfg.start = s;
}

SceneConfig load_scene_config(const std::string& path) {
  SceneConfig cfg;
  cfg.path = path;
  const toml::table root_table = parse_toml_file(path, &cfg.text);
  const TomlTable root(root_table, path, "");
  root.only(
      {"model", "plan", "rules", "materials", "luminaires", "circuits", "lighting", "visibility", "start"});
  read_model(root, cfg);
  read_plan(root, cfg);
  read_rules(root, cfg);
  read_materials(root, cfg);
  read_luminaires(root, cfg);
  read_circuits(root, cfg);
  read_lighting(root, cfg);
  read_visibility(root, cfg);
  read_start(root, cfg);
  return cfg;
}

}  // namespace walk::compiler
