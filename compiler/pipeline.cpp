#include "compiler/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <memory>
#include <numbers>

#include "common/hash.hpp"
#include "compiler/cleanup/cleanup.hpp"
#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/geometry/coarse_mesh.hpp"
#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/openings.hpp"
#include "compiler/geometry/seal_gaps.hpp"
#include "compiler/geometry/t_junctions.hpp"
#include "compiler/import/import_model.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/lod/simplify_clusters.hpp"
#include "compiler/radiosity/compact_light.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "compiler/radiosity/vertex_light.hpp"
#include "compiler/scene/apply_rules.hpp"
#include "compiler/scene/luminaires.hpp"
#include "compiler/scene/work_budget.hpp"
#include "compiler/textures/polygon_textures.hpp"
#include "compiler/visibility/compute_cells.hpp"
#include "model/error.hpp"
#include "model/version.hpp"

namespace walk::compiler {
namespace {

// Reflectance given to luminaire panels when they are drawn (their emission dominates anyway).
constexpr double kPanelReflectance = 0.8;
// Automatic exposure maps this percentile of lit-surface radiosity to 1/kExposureHeadroom of white.
constexpr double kExposurePercentile = 0.95;
constexpr double kExposureHeadroom = 0.8;

class StageTimer {
 public:
  StageTimer(std::vector<StageReport>& stages, std::string name) : stages_(stages) {
    StageReport report;
    report.name = std::move(name);
    stages_.push_back(std::move(report));
    start_ = std::chrono::steady_clock::now();
  }
  StageReport& report() { return stages_.back(); }
  void done(std::uint64_t in, std::uint64_t out, std::string detail = {}) {
    auto& r = stages_.back();
    r.ran = true;
    r.items_in = in;
    r.items_out = out;
    r.detail = std::move(detail);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    spdlog::info("stage {}: {} -> {} in {:.3f} s {}", r.name, in, out, r.seconds, r.detail);
  }
  void reused(std::string why) {
    stages_.back().reused = true;
    stages_.back().detail = std::move(why);
    stages_.back().seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    spdlog::info("stage {}: reused ({})", stages_.back().name, stages_.back().detail);
  }
  void skipped(std::string why) {
    stages_.back().detail = std::move(why);
    spdlog::info("stage {}: not run ({})", stages_.back().name, stages_.back().detail);
  }

 private:
  std::vector<StageReport>& stages_;
  std::chrono::steady_clock::time_point start_;
};

bool drawn(model::Role r) {
  return r == model::Role::Opaque || r == model::Role::Glass;
}

model::Polygon panel_polygon(const model::Luminaire& l) {
  const model::Vec3 u = glm::normalize(l.u_axis) * (0.5 * l.width);
  const model::Vec3 v = glm::normalize(glm::cross(l.normal, l.u_axis)) * (0.5 * l.height);
  model::Polygon p;
  p.vertices = {l.position - u - v, l.position + u - v, l.position + u + v, l.position - u + v};
  p.role = model::Role::Luminaire;
  p.name = l.name;
  return p;
}

template <typename T>
std::uint64_t hash_vector(std::uint64_t h, const std::vector<T>& v) {
  return hash_bytes(h, v.data(), v.size() * sizeof(T));
}

// The light solve depends only on the meshed surfaces, their reflectances, the luminaires and the lighting
// knobs: hashing exactly these lets a compile that changed anything else (exposure, ambient, cells) reuse it.
std::uint64_t light_inputs_hash(const model::BundleContents& out,
                                const std::vector<model::Luminaire>& luminaires, const LightingConfig& l,
                                std::size_t circuits, std::uint64_t compiler_identity) {
  std::uint64_t h = compiler_identity;
  h = hash_vector(h, out.vertices);
  h = hash_vector(h, out.indices);
  for (const auto& p : out.polygons)
    h = hash_bytes(h, &p, offsetof(model::PolygonRecord, name));  // not the name
  for (const auto& l2 : out.luminaires) h = hash_bytes(h, &l2, offsetof(model::LuminaireRecord, name));
  const double knobs[] = {double(l.method), l.grid,     double(l.samples_per_luminaire),
                          l.rays_per_watt,  l.residual, double(circuits)};
  h = hash_bytes(h, knobs, sizeof knobs);
  for (const auto& lum : luminaires) {  // what the bundle's records leave out
    const double shape[] = {double(lum.kind), lum.cone,       lum.exponent,
                            lum.position.x,   lum.position.y, lum.position.z};
    h = hash_bytes(h, shape, sizeof shape);
  }
  return hash_bytes(h, l.ray_caster.data(), l.ray_caster.size());
}

const model::StageRecord* previous_stage(const model::Bundle* previous, const char* name) {
  if (!previous) return nullptr;
  for (const auto& s : previous->stages())
    if (previous->string(s.name) == name) return &s;
  return nullptr;
}

}  // namespace

// The compiler is an input too: its version (git describe) and revision constant. A build from an edited tree
// carries the same version for every edit, so its executable is hashed as well: "up to date" never hides a
// compiler change during development, and a release build does not read its own 60 MB to say who it is.
std::uint64_t compiler_identity() {
  static const std::uint64_t identity = [] {
    const std::string v = version();
    std::uint64_t h = hash_bytes(kCompilerRevision, v.data(), v.size());
    if (v.find("dirty") != std::string::npos || v.find("+git.") == std::string::npos)
      h = hash_file(h, "/proc/self/exe");
    return h;
  }();
  return identity;
}

std::uint64_t scene_hash(const SceneConfig& config) {
  std::uint64_t h = compiler_identity();
  h = hash_bytes(h, config.text.data(), config.text.size());
  h = hash_file(h, config.model_file);
  // What a mesh model reads beside itself (its .mtl, albedo maps) and the scene's texture folders: an
  // edited texture must recompile, not be taken for the bundle's own.
  std::vector<std::filesystem::path> folders{std::filesystem::path(config.model_file).parent_path()};
  for (const auto& d : config.texture_dirs) folders.emplace_back(d);
  for (const auto& folder : folders) {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
      std::string ext = entry.path().extension().string();
      for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (ext == ".mtl" || ext == ".png" || ext == ".jpg" || ext == ".jpeg") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) h = hash_file(h, f.string());
  }
  return h;
}

CompileResult compile_scene(const SceneConfig& config, const CompileOptions& options,
                            const model::Bundle* previous) {
  CompileResult result;
  auto& stages = result.stages;
  model::Model model;
  ImportReport imported;
  {
    StageTimer t(stages, "import");
    model = import_model(config, &imported);
    check_coordinates(model, config.model_file);
    t.done(0, model.polygons.size(), imported.format + ": " + imported.detail);
  }
  {
    StageTimer t(stages, "rules");
    const auto s = apply_rules(model, config);
    using model::Role;
    t.done(model.polygons.size() + s.dropped, model.polygons.size(),
           fmt::format("opaque {} glass {} opening {} dropped {} flipped {}", s.per_role[0], s.per_role[1],
                       s.per_role[2], s.dropped, s.flipped));
    if (std::none_of(model.polygons.begin(), model.polygons.end(),
                     [](const auto& p) { return drawn(p.role); }))
      throw Error(located(config.model_file, 0,
                          "empty model: no opaque or glass faces after the scene's rules",
                          "check the [[rules]] in " + config.path));
  }
  double weld_tolerance = 0.0;  // metres; clean-up's, which also sets what counts as a vertex on a seam
  {
    // After the rules, which drop annotation layers (so they do not set the weld tolerance) and install the
    // config's materials (the file's own come back after them).
    StageTimer t(stages, "cleanup");
    append_imported_materials(model, config, imported);
    const std::size_t before = model.polygons.size();
    // Before the weld tolerance is taken from the model's size, which one stray face would inflate.
    const StrayStats strays = remove_strays(model, config.keep_outliers);
    if (strays.faces > 0)
      spdlog::warn(
          "{}: {} face(s) lie far from the rest of the model, the first at ({:.1f}, {:.1f}, {:.1f}) m "
          "(source line or face {}); {} (set [model] outliers = \"{}\" in {} to change this)",
          config.model_file, strays.faces, strays.first.x, strays.first.y, strays.first.z, strays.first_line,
          config.keep_outliers ? "kept" : "left out", config.keep_outliers ? "drop" : "keep", config.path);
    const CleanupStats s = clean_up(model, config.weld_metres);
    weld_tolerance = s.weld_tolerance;
    if (std::none_of(model.polygons.begin(), model.polygons.end(),
                     [](const auto& p) { return drawn(p.role); }))
      throw Error(located(
          config.model_file, 0,
          fmt::format("no face is left to draw after clean-up ({}; {})", strays.summary(), s.summary()),
          "check the model's units and geometry; nothing was written"));
    t.done(before, model.polygons.size(), strays.summary() + "; " + s.summary());
  }
  {
    StageTimer t(stages, "recentre");
    const model::Bounds b = bounds_of(model);
    // A whole-metre local origin at the model's centre: float rendering then keeps sub-millimetre precision
    // even for drawings placed far from the world origin.
    model.origin = glm::round(b.centre());
    for (auto& p : model.polygons) {
      for (auto& v : p.vertices) v -= model.origin;
      for (auto& hole : p.holes)
        for (auto& v : hole) v -= model.origin;
      if (p.texture_map) p.texture_map->translate(-model.origin);
    }
    for (auto& l : model.luminaires) l.position -= model.origin;  // imported lights move with the geometry
    t.done(model.polygons.size() + model.luminaires.size(), model.polygons.size() + model.luminaires.size());
  }
  {
    StageTimer t(stages, "openings");
    const bool needed = std::any_of(model.polygons.begin(), model.polygons.end(), [](const auto& p) {
      return p.role == model::Role::Opening || p.role == model::Role::Glass;
    });
    if (!needed) {
      t.skipped("scene has no openings or glass");
    } else {
      const std::size_t before = model.polygons.size();
      const auto s = cut_openings(model);
      t.done(before, model.polygons.size(),
             fmt::format("hosts cut {} openings {} glass {} unmatched {}", s.hosts_cut, s.openings_cut,
                         s.glass_cut, s.unmatched));
    }
  }
  {
    // After the openings, whose cut-outs are holes the seal must keep (they are far wider than a slit).
    StageTimer t(stages, "seal");
    if (!(config.seal_metres > 0.0)) {
      t.skipped("scene seals no slits ([model] seal)");
    } else {
      const std::size_t before = model.polygons.size();
      const SealStats s = seal_gaps(model, config.seal_metres);
      t.done(before, model.polygons.size(), fmt::format("width {} m: {}", config.seal_metres, s.summary()));
    }
  }
  {
    StageTimer t(stages, "luminaires");
    if (!config.panels.enabled && config.luminaires.empty() && config.circuits.empty()) {
      t.skipped("scene adds no luminaires and regroups no circuits");
    } else {
      const auto s = add_luminaires(model, config);
      t.done(model.groups.size(), model.luminaires.size(),
             fmt::format("per-room {} explicit {} rooms without ceiling {} circuits {}", s.added_per_group,
                         s.explicit_panels, s.groups_without_ceiling, model.circuits.size()));
    }
  }

  // What the mesh and light stages would cost, refused before they allocate anything.
  check_patch_budget(model, config, physical_memory_bytes());
  check_ray_budget(model, config);

  auto& out = result.bundle;
  std::vector<SurfaceSample> samples;        // one per vertex of a lit polygon
  std::vector<std::uint32_t> sample_vertex;  // bundle vertex of each sample
  std::vector<Triangle> occluders;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> panel_polygons;  // (bundle polygon, luminaire)
  PatchSet patches;  // vertices numbered as the bundle's, in double precision
  {
    StageTimer t(stages, "mesh");
    // Area luminaires are drawn as the panels they are; point and spot lights have no surface.
    std::vector<model::Polygon> panels;
    std::vector<std::uint32_t> panel_luminaire;
    for (std::uint32_t i = 0; i < model.luminaires.size(); ++i) {
      if (model.luminaires[i].kind != model::LuminaireKind::Area) continue;
      panels.push_back(panel_polygon(model.luminaires[i]));
      panel_luminaire.push_back(i);
    }
    // The dicing cell of a polygon's mesh: luminaire panels undiced, everything else on the lighting grid.
    auto dice_size = [&](const model::Polygon& poly) {
      return poly.role == model::Role::Luminaire ? 0.0 : config.lighting.grid;
    };
    std::size_t coarse_fallbacks = 0;
    std::size_t coarse_unrepaired = 0;           // coarse forms drawn without their seam repair
    std::vector<const model::Polygon*> emitted;  // the model polygon of each bundle polygon
    auto emit = [&](const model::Polygon& poly, std::uint32_t luminaire, const PolygonMesh& mesh,
                    const PolygonMesh& coarse) {
      const double cell_size = dice_size(poly);
      if (mesh.triangles.empty()) return;
      const auto id = static_cast<std::uint32_t>(out.polygons.size());
      const auto first_vertex = static_cast<std::uint32_t>(out.vertices.size());
      const model::Rgb albedo = poly.role == model::Role::Luminaire
                                    ? model::Rgb(kPanelReflectance)
                                    : model.materials[poly.material].reflectance;
      for (const auto& v : mesh.vertices) {
        model::VertexRecord r{};
        for (int a = 0; a < 3; ++a) {
          r.position[a] = static_cast<float>(v[a]);
          r.normal[a] = static_cast<float>(mesh.normal[a]);
          r.albedo[a] = static_cast<float>(albedo[a]);
        }
        r.polygon = id;
        patches.vertices.push_back(v);
        if (poly.role != model::Role::Luminaire) {
          samples.push_back({v, mesh.normal, albedo});
          sample_vertex.push_back(static_cast<std::uint32_t>(out.vertices.size()));
        }
        out.vertices.push_back(r);
      }
      const auto first_index = static_cast<std::uint32_t>(out.indices.size());
      for (std::uint32_t i : mesh.triangles) out.indices.push_back(first_vertex + i);
      for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3)
        patches.add(first_vertex + mesh.triangles[i], first_vertex + mesh.triangles[i + 1],
                    first_vertex + mesh.triangles[i + 2], albedo, id);
      model::PolygonRecord rec{};
      rec.first_index = first_index;
      rec.index_count = static_cast<std::uint32_t>(mesh.triangles.size());
      rec.first_vertex = first_vertex;
      rec.vertex_count = static_cast<std::uint32_t>(mesh.vertices.size());
      rec.material = poly.role == model::Role::Luminaire ? 0 : poly.material;
      rec.group = poly.group;
      rec.role = static_cast<std::uint32_t>(poly.role);
      rec.name = out.add_string(poly.name);
      out.polygons.push_back(rec);
      emitted.push_back(&poly);
      if (luminaire != UINT32_MAX) {
        out.luminaires[luminaire].name = rec.name;
        panel_polygons.emplace_back(id, luminaire);
      }
      // The coarse form drawn while moving: the polygon's fewest triangles over its diced vertices, or the
      // diced triangles themselves where no match is found (never seen on the shared models; counted).
      // A panel is meshed undiced already: its mesh is its coarse form.
      auto coarse_local = cell_size > 0.0 ? coarse_triangles(mesh, coarse) : std::optional(mesh.triangles);
      // A seam vertex the coarse repair inserted but the diced one did not (it fell within the weld
      // distance of a diced vertex): the unrepaired coarse form, as before the repair.
      if (!coarse_local && cell_size > 0.0) {
        coarse_local = coarse_triangles(mesh, mesh_polygon(poly, 0.0));
        ++coarse_unrepaired;
      }
      if (!coarse_local) ++coarse_fallbacks;
      out.coarse_ranges.push_back({static_cast<std::uint32_t>(out.coarse_indices.size()), 0});
      for (std::uint32_t i : coarse_local ? *coarse_local : mesh.triangles)
        out.coarse_indices.push_back(first_vertex + i);
      out.coarse_ranges.back().index_count =
          static_cast<std::uint32_t>(out.coarse_indices.size()) - out.coarse_ranges.back().first_index;
      // Shadow-ray occluders for the direct method only (radiosity casts against its own patches), from the
      // coarse triangulation: fewer triangles, same surface.
      if (drawn(poly.role) && config.lighting.method == LightingMethod::Direct) {
        for (std::size_t i = 0; i + 2 < coarse.triangles.size(); i += 3)
          occluders.push_back({coarse.vertices[coarse.triangles[i]], coarse.vertices[coarse.triangles[i + 1]],
                               coarse.vertices[coarse.triangles[i + 2]], id});
      }
    };
    for (const auto& l : model.luminaires) {
      model::LuminaireRecord r{};
      for (int a = 0; a < 3; ++a) {
        r.position[a] = static_cast<float>(l.position[a]);
        r.normal[a] = static_cast<float>(l.normal[a]);
        r.u_axis[a] = static_cast<float>(l.u_axis[a]);
        r.power[a] = static_cast<float>(l.power[a]);
      }
      r.width = static_cast<float>(l.width);
      r.height = static_cast<float>(l.height);
      r.circuit = l.circuit;
      out.luminaires.push_back(r);
    }
    std::vector<std::pair<const model::Polygon*, std::uint32_t>> to_emit;  // (polygon, luminaire or none)
    for (const auto& p : model.polygons)
      if (drawn(p.role)) to_emit.emplace_back(&p, UINT32_MAX);
    for (std::uint32_t i = 0; i < panels.size(); ++i) to_emit.emplace_back(&panels[i], panel_luminaire[i]);
    std::vector<PolygonMesh> meshes;
    meshes.reserve(to_emit.size());
    for (const auto& [poly, luminaire] : to_emit) meshes.push_back(mesh_polygon(*poly, dice_size(*poly)));
    // Seams between polygons diced apart: vertices that lie on a neighbour's edge within the weld distance
    // become vertices of that edge too, so float rounding cannot open a crack along a slanted seam.
    const TJunctionStats seams = repair_t_junctions(meshes, weld_tolerance);
    // The coarse forms drawn while moving, repaired alike. A neighbour's corner on a seam was inserted into
    // this polygon's diced mesh above, so the coarse form still finds every vertex among the diced ones.
    std::vector<PolygonMesh> coarse_meshes;
    TJunctionStats coarse_seams;
    if (config.lighting.grid > 0.0) {
      coarse_meshes.reserve(to_emit.size());
      for (std::size_t i = 0; i < to_emit.size(); ++i)
        coarse_meshes.push_back(dice_size(*to_emit[i].first) > 0.0 ? mesh_polygon(*to_emit[i].first, 0.0)
                                                                   : meshes[i]);
      coarse_seams = repair_t_junctions(coarse_meshes, weld_tolerance);
    }
    for (std::size_t i = 0; i < to_emit.size(); ++i)
      emit(*to_emit[i].first, to_emit[i].second, meshes[i],
           coarse_meshes.empty() ? meshes[i] : coarse_meshes[i]);
    add_polygon_textures(model, emitted, out);
    t.done(model.polygons.size() + panels.size(), out.polygons.size(),
           fmt::format("{} vertices {} triangles grid {} m; coarse {} triangles ({} polygons kept diced); "
                       "T-junctions {} vertices into {} triangles (coarse {} into {}, {} left unrepaired); "
                       "textures {} ({} MiB)",
                       out.vertices.size(), out.indices.size() / 3, config.lighting.grid,
                       out.coarse_indices.size() / 3, coarse_fallbacks, seams.vertices_inserted,
                       seams.triangles_split, coarse_seams.vertices_inserted, coarse_seams.triangles_split,
                       coarse_unrepaired, out.textures.size(), out.texels.size() >> 20));
  }

  const std::size_t circuits = model.circuits.size();
  out.light.assign(out.vertices.size() * circuits * 3, 0.0f);
  {
    StageTimer t(stages, "light");
    const std::uint64_t light_hash =
        light_inputs_hash(out, model.luminaires, config.lighting, circuits, compiler_identity());
    t.report().input_hash = light_hash;
    const model::StageRecord* before = previous_stage(previous, "light");
    if (model.luminaires.empty()) {
      t.skipped("no luminaires: display shows ambient light only");
    } else if (before && before->input_hash == light_hash && before->ran != 0 &&
               previous->light().size() == out.light.size()) {
      out.light.assign(previous->light().begin(), previous->light().end());
      out.polygon_light.assign(previous->polygon_light().begin(), previous->polygon_light().end());
      t.reused("surfaces, materials, luminaires and lighting knobs unchanged since " + previous->path());
    } else if (config.lighting.method == LightingMethod::Radiosity) {
      std::vector<AreaEmitter> emitters;
      for (std::uint32_t p = 0; p < patches.patches.size(); ++p) {
        for (const auto& [polygon, luminaire] : panel_polygons) {
          if (patches.patches[p].polygon != polygon) continue;
          const auto& l = model.luminaires[luminaire];
          emitters.push_back({p, l.circuit, l.power / (l.width * l.height)});
        }
      }
      std::vector<PointEmitter> points;
      for (const auto& l : model.luminaires) {
        if (l.kind == model::LuminaireKind::Area) continue;
        points.push_back({l.position, l.normal,
                          l.kind == model::LuminaireKind::Spot ? l.cone : std::numbers::pi,
                          l.kind == model::LuminaireKind::Spot ? l.exponent : 0.0, l.power, l.circuit});
      }
      RadiosityOptions ro;
      ro.rays_per_watt = config.lighting.rays_per_watt;
      ro.residual = config.lighting.residual;
      ro.threads = options.threads;
      ro.caster = config.lighting.ray_caster;
      const RadiosityResult r = solve_radiosity(patches, emitters, points, circuits, ro);
      out.light = vertex_radiosity(patches, r);
      out.polygon_light = polygon_radiosity(patches, r, out.polygons.size());
      const auto& s = r.stats;
      t.done(
          patches.patches.size(), s.rays,
          fmt::format("radiosity: {} patches, {} circuits, {} rays in {} shots / {} rounds, {:.2f} Mrays/s, "
                      "residual {:.2f}%, absorbed {:.1f} W escaped {:.1f} W of {:.1f} W",
                      patches.patches.size(), circuits, s.rays, s.shots, s.rounds, s.rays / s.seconds * 1e-6,
                      100.0 * s.unshot / s.emitted, s.absorbed, s.escaped, s.emitted));
    } else {
      const TriangleBvh bvh(std::move(occluders));
      DirectLightStats s;
      const auto light = direct_light(samples, model.luminaires, circuits, bvh,
                                      {config.lighting.samples_per_luminaire, options.threads}, &s);
      for (std::size_t i = 0; i < samples.size(); ++i)
        std::copy_n(&light[i * circuits * 3], circuits * 3, &out.light[sample_vertex[i] * circuits * 3]);
      // Panels glow with their exitance Phi/A in their own circuit.
      for (const auto& [polygon, luminaire] : panel_polygons) {
        const auto& poly = out.polygons[polygon];
        const auto& l = out.luminaires[luminaire];
        for (std::uint32_t v = poly.first_vertex; v < poly.first_vertex + poly.vertex_count; ++v)
          for (int c = 0; c < 3; ++c)
            out.light[(v * circuits + l.circuit) * 3 + c] = l.power[c] / (l.width * l.height);
      }
      t.done(samples.size(), s.shadow_rays,
             fmt::format("direct: {} shadow rays, {} occluded, {} luminaires, {} circuits", s.shadow_rays,
                         s.occluded, model.luminaires.size(), circuits));
    }
  }

  CompactLight compact;
  {
    StageTimer t(stages, "compact");
    if (circuits == 0 || model.luminaires.empty()) {
      t.skipped("no light to compact");
    } else {
      compact = compact_light(out.light, out.vertices.size(), circuits);
      out.compact_colour = compact.colour;
      out.compact_intensity = compact.intensity;
      t.done(out.light.size() * sizeof(float), compact.colour.size() * 4 + compact.intensity.size(),
             fmt::format("error all on {:.2f}% RMS, worst circuit {:.2f}% RMS",
                         100.0 * compact.rms_error_all_on, 100.0 * compact.worst_circuit_rms));
    }
  }

  // Meta, materials, groups, circuits, the single cell.
  model::Bounds local;
  for (const auto& v : out.vertices) local.add({v.position[0], v.position[1], v.position[2]});
  auto& meta = out.meta;
  for (int a = 0; a < 3; ++a) {
    meta.origin[a] = model.origin[a];
    meta.bounds_min[a] = static_cast<float>(local.min[a]);
    meta.bounds_max[a] = static_cast<float>(local.max[a]);
  }
  meta.ambient = static_cast<float>(config.lighting.ambient);
  meta.scene_hash = scene_hash(config);
  meta.circuit_count = static_cast<std::uint32_t>(circuits);
  meta.compiler_version = out.add_string(std::string("walk ") + version());
  if (config.lighting.exposure) {
    meta.exposure = static_cast<float>(*config.lighting.exposure);
  } else {
    std::vector<float> totals;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      float sum = 0.0f;
      for (std::size_t c = 0; c < circuits * 3; ++c) sum += out.light[sample_vertex[i] * circuits * 3 + c];
      if (sum > 0.0f) totals.push_back(sum / 3.0f);
    }
    float exposure = 1.0f;
    if (!totals.empty()) {
      auto nth = totals.begin() + static_cast<std::ptrdiff_t>(kExposurePercentile * (totals.size() - 1));
      std::nth_element(totals.begin(), nth, totals.end());
      exposure = static_cast<float>(*nth / kExposureHeadroom);
    }
    meta.exposure = std::max(exposure, 1e-6f);
  }
  for (const auto& m : model.materials)
    out.materials.push_back(
        {{float(m.reflectance.r), float(m.reflectance.g), float(m.reflectance.b)}, out.add_string(m.name)});
  for (const auto& g : model.groups) out.groups.push_back({out.add_string(g)});
  for (std::size_t c = 0; c < model.circuits.size(); ++c)
    out.circuits.push_back({out.add_string(model.circuits[c].name), float(model.circuits[c].default_level),
                            compact.scale.empty() ? 0.0f : compact.scale[c]});
  {
    StageTimer t(stages, "cells");
    VisibilityConfig vis = config.visibility;
    if (vis.threads == 0) vis.threads = options.threads;
    vis.source = config.path;
    // Inside-flood seeds: the start at eye height, and a point in the room below each luminaire.
    constexpr double kSeedEyeHeight = 1.2;        // metres above the start point, which is on a floor
    constexpr double kSeedBelowLuminaire = 0.25;  // metres along the luminaire's normal, into its room
    if (config.start)
      vis.seeds.push_back(config.start->position - model.origin + model::Vec3(0.0, 0.0, kSeedEyeHeight));
    for (const auto& l : out.luminaires)
      vis.seeds.push_back(model::Vec3(l.position[0], l.position[1], l.position[2]) +
                          kSeedBelowLuminaire * model::Vec3(l.normal[0], l.normal[1], l.normal[2]));
    const auto counts = compute_cells(out, vis);
    t.done(counts.polygons_in, counts.cells_out, counts.detail);
  }
  {
    StageTimer t(stages, "lod");
    const LodCounts lod = simplify_clusters(out, options.threads);
    if (lod.simplified == 0) {
      t.skipped("no cluster of " + std::to_string(kLodMinTriangles) + " triangles or more to simplify");
    } else {
      t.done(lod.triangles, lod.level_triangles.back(),
             std::to_string(lod.simplified) + " of " + std::to_string(lod.clusters) + " clusters; " +
                 std::to_string(lod.triangles) + " triangles -> " + std::to_string(lod.level_triangles[0]) +
                 ", " + std::to_string(lod.level_triangles[1]) + ", " +
                 std::to_string(lod.level_triangles[2]));
    }
  }
  for (const auto& s : stages)
    out.stages.push_back({out.add_string(s.name), s.ran ? 1u : (s.reused ? 2u : 0u),
                          s.input_hash != 0 ? s.input_hash : meta.scene_hash, s.seconds, s.items_in,
                          s.items_out});
  return result;
}

bool compile_to_file(const std::string& config_path, const std::string& output, bool force,
                     std::vector<StageReport>* stages, const CompileOptions& options) {
  const SceneConfig config = load_scene_config(config_path);
  std::unique_ptr<model::Bundle> previous;
  if (std::filesystem::exists(output)) {
    try {
      previous = model::Bundle::open(output);
    } catch (const Error& e) {
      spdlog::info("previous bundle not reusable: {}", e.what());  // an unreadable old bundle is rebuilt
    }
  }
  if (!force && previous && previous->meta().scene_hash == scene_hash(config)) return false;
  CompileResult result = compile_scene(config, options, force ? nullptr : previous.get());
  previous.reset();  // unmap before the rename replaces the file
  model::write_bundle(output, result.bundle);
  if (stages) *stages = std::move(result.stages);
  return true;
}

}  // namespace walk::compiler
