// mesh: every drawn polygon and luminaire panel diced on the lighting grid (the light's patches) and meshed
// again undiced (the coarse form drawn while moving), seams repaired, written as the bundle's vertices,
// indices and polygon records; also the light stage's samples, patches and occluders. The work budgets of
// the mesh and light stages are checked first, before anything is allocated.
#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <optional>
#include <span>

#include "compiler/geometry/coarse_mesh.hpp"
#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/t_junctions.hpp"
#include "compiler/lighting/light_refinement.hpp"
#include "compiler/scene/work_budget.hpp"
#include "compiler/stages/stages.hpp"
#include "compiler/textures/polygon_textures.hpp"
#include "model/luminaire_shapes.hpp"

namespace walk::compiler {
namespace {

// Reflectance given to luminaire panels when they are drawn (their emission dominates anyway).
constexpr double kPanelReflectance = 0.8;
constexpr std::uint32_t kNoLuminaire = UINT32_MAX;

model::Polygon panel_polygon(const model::Luminaire& l) {
  const auto corners = model::panel_corners(l);
  model::Polygon p;
  p.vertices.assign(corners.begin(), corners.end());
  p.role = model::Role::Luminaire;
  p.name = l.name;
  return p;
}

model::LuminaireRecord luminaire_record(const model::Luminaire& l) {
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
  return r;
}

class MeshStage final : public Stage {
 public:
  const char* name() const override { return "mesh"; }
  StageOutcome run(CompileState& s, std::uint64_t) override;

 private:
  // The dicing cell of a polygon's mesh: luminaire panels undiced, everything else on the lighting grid.
  static bool refines_by_light(const CompileState& s) {
    const auto& l = s.config.lighting;
    return l.method == LightingMethod::Radiosity && l.gather_direct && l.refine && l.target_error &&
           l.grid > 0.0 && !s.model.luminaires.empty();
  }

  // With a target error and gathered direct light, the diced meshes are subdivided further where the
  // direct light bends more than the target allows (compiler/lighting/light_refinement.hpp).
  // `direct`: the direct light it gathered, per mesh (light_refinement.hpp).
  static LightRefinementStats refine_by_light(
      const CompileState& s, const std::vector<std::pair<const model::Polygon*, std::uint32_t>>& to_emit,
      std::vector<PolygonMesh>& meshes, std::vector<SparseLight>& direct) {
    const auto& l = s.config.lighting;
    if (!refines_by_light(s)) return {};
    std::vector<bool> lit;
    std::vector<Triangle> occluders;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      lit.push_back(to_emit[i].second == kNoLuminaire);  // panels glow; they are no receivers or occluders
      if (!lit.back()) continue;
      const auto& m = meshes[i];
      for (std::size_t t = 0; t + 2 < m.triangles.size(); t += 3)
        occluders.push_back({m.vertices[m.triangles[t]], m.vertices[m.triangles[t + 1]],
                             m.vertices[m.triangles[t + 2]], static_cast<std::uint32_t>(i)});
    }
    const TriangleBvh bvh(std::move(occluders));
    LightRefinementOptions o;
    o.tolerance = *l.target_error;
    o.min_edge = std::max(kMinGrid, l.grid / 16.0);
    o.samples_per_luminaire = l.samples_per_luminaire;
    o.threads = s.options.threads;
    return refine_by_direct_light(meshes, lit, s.model.luminaires, bvh, o, &direct);
  }

  double dice_size(const CompileState& s, const model::Polygon& poly) const {
    return poly.role == model::Role::Luminaire ? 0.0 : s.config.lighting.grid;
  }
  // Writes one polygon's diced mesh and coarse form into the bundle and the light stage's inputs.
  // `solve`: the triangles the radiosity solver shoots between (the dicing before light refinement, whose
  // vertices are the first of `mesh`'s), or `mesh` itself. `direct`: the refinement's direct light at the
  // first of `mesh`'s vertices (a row each), when it ran.
  void emit(CompileState& s, const model::Polygon& poly, std::uint32_t luminaire, const PolygonMesh& mesh,
            const PolygonMesh& coarse, const PolygonMesh& solve, const SparseLight* direct);

  bool refined_direct_ = false;  // the refinement's direct light is handed to the light stage
  std::size_t coarse_fallbacks_ = 0;
  std::size_t coarse_unrepaired_ = 0;           // coarse forms drawn without their seam repair
  std::vector<const model::Polygon*> emitted_;  // the model polygon of each bundle polygon
};

void MeshStage::emit(CompileState& s, const model::Polygon& poly, std::uint32_t luminaire,
                     const PolygonMesh& mesh, const PolygonMesh& coarse, const PolygonMesh& solve,
                     const SparseLight* direct) {
  auto& out = s.out;
  const double cell_size = dice_size(s, poly);
  if (mesh.triangles.empty()) return;
  const auto id = static_cast<std::uint32_t>(out.polygons.size());
  const auto first_vertex = static_cast<std::uint32_t>(out.vertices.size());
  const model::Rgb albedo = poly.role == model::Role::Luminaire
                                ? model::Rgb(kPanelReflectance)
                                : s.model.materials[poly.material].reflectance;
  const std::size_t known = direct ? direct->rows() : 0;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const model::Vec3& v = mesh.vertices[i];
    model::VertexRecord r{};
    for (int a = 0; a < 3; ++a) {
      r.position[a] = static_cast<float>(v[a]);
      r.normal[a] = static_cast<float>(mesh.normal[a]);
      r.albedo[a] = static_cast<float>(albedo[a]);
    }
    r.polygon = id;
    s.patches.vertices.push_back(v);
    if (poly.role != model::Role::Luminaire) {
      s.samples.push_back({v, mesh.normal, albedo});
      s.sample_vertex.push_back(static_cast<std::uint32_t>(out.vertices.size()));
      if (refined_direct_) {
        s.sample_refined.push_back(i < known);
        s.sample_direct.append_row(i < known ? direct->row(i) : std::span<const CircuitLight>());
      }
    }
    out.vertices.push_back(r);
  }
  const auto first_index = static_cast<std::uint32_t>(out.indices.size());
  for (std::uint32_t i : mesh.triangles) out.indices.push_back(first_vertex + i);
  for (std::size_t i = 0; i + 2 < solve.triangles.size(); i += 3)
    s.patches.add(first_vertex + solve.triangles[i], first_vertex + solve.triangles[i + 1],
                  first_vertex + solve.triangles[i + 2], albedo, id);
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
  emitted_.push_back(&poly);
  if (luminaire != kNoLuminaire) {
    out.luminaires[luminaire].name = rec.name;
    s.panel_polygons.emplace_back(id, luminaire);
  }
  // The coarse form drawn while moving: the polygon's fewest triangles over its diced vertices, or the
  // diced triangles themselves where no match is found (never seen on the shared models; counted). A panel
  // is meshed undiced already: its mesh is its coarse form.
  auto coarse_local = cell_size > 0.0 ? coarse_triangles(mesh, coarse) : std::optional(mesh.triangles);
  // A seam vertex the coarse repair inserted but the diced one did not (it fell within the weld distance of
  // a diced vertex): the unrepaired coarse form, as before the repair.
  if (!coarse_local && cell_size > 0.0) {
    coarse_local = coarse_triangles(mesh, mesh_polygon(poly, 0.0));
    ++coarse_unrepaired_;
  }
  if (!coarse_local) ++coarse_fallbacks_;
  out.coarse_ranges.push_back({static_cast<std::uint32_t>(out.coarse_indices.size()), 0});
  for (std::uint32_t i : coarse_local ? *coarse_local : mesh.triangles)
    out.coarse_indices.push_back(first_vertex + i);
  out.coarse_ranges.back().index_count =
      static_cast<std::uint32_t>(out.coarse_indices.size()) - out.coarse_ranges.back().first_index;
  // Shadow-ray occluders for gathered direct light and the light stage's checks between vertices
  // (radiosity shoots against its own patches), from the coarse triangulation: fewer triangles, same
  // surface.
  if (drawn(poly.role)) {
    for (std::size_t i = 0; i + 2 < coarse.triangles.size(); i += 3)
      s.occluders.push_back({coarse.vertices[coarse.triangles[i]], coarse.vertices[coarse.triangles[i + 1]],
                             coarse.vertices[coarse.triangles[i + 2]], id});
  }
}

StageOutcome MeshStage::run(CompileState& s, std::uint64_t) {
  // What the mesh and light stages would cost, refused before they allocate anything.
  check_patch_budget(s.model, s.config, physical_memory_bytes());
  check_ray_budget(s.model, s.config);

  auto& out = s.out;
  // Area luminaires are drawn as the panels they are; point and spot lights have no surface.
  std::vector<model::Polygon> panels;
  std::vector<std::uint32_t> panel_luminaire;
  for (std::uint32_t i = 0; i < s.model.luminaires.size(); ++i) {
    if (s.model.luminaires[i].kind != model::LuminaireKind::Area) continue;
    panels.push_back(panel_polygon(s.model.luminaires[i]));
    panel_luminaire.push_back(i);
  }
  for (const auto& l : s.model.luminaires) out.luminaires.push_back(luminaire_record(l));
  model::store_luminaire_shapes(s.model.luminaires, out);

  std::vector<std::pair<const model::Polygon*, std::uint32_t>> to_emit;  // (polygon, luminaire or none)
  for (const auto& p : s.model.polygons)
    if (drawn(p.role)) to_emit.emplace_back(&p, kNoLuminaire);
  for (std::uint32_t i = 0; i < panels.size(); ++i) to_emit.emplace_back(&panels[i], panel_luminaire[i]);
  std::vector<PolygonMesh> meshes;
  meshes.reserve(to_emit.size());
  for (const auto& [poly, luminaire] : to_emit) meshes.push_back(mesh_polygon(*poly, dice_size(s, *poly)));
  // Refinement only appends vertices, and so does the seam repair below: the dicing's vertices stay the
  // first of each mesh, so its triangles still index the refined mesh's vertices.
  std::vector<PolygonMesh> diced;
  if (refines_by_light(s)) diced = meshes;
  std::vector<SparseLight> direct;
  const LightRefinementStats refined = refine_by_light(s, to_emit, meshes, direct);
  if (refined.edges_split == 0) diced.clear();
  refined_direct_ = !diced.empty() && refined.circuits > 0;
  s.patches_coarser_than_display = !diced.empty();
  // Seams between polygons diced apart: vertices that lie on a neighbour's edge within the weld distance
  // become vertices of that edge too, so float rounding cannot open a crack along a slanted seam.
  const TJunctionStats seams = repair_t_junctions(meshes, s.weld_tolerance);
  // The coarse forms drawn while moving, repaired alike. A neighbour's corner on a seam was inserted into
  // this polygon's diced mesh above, so the coarse form still finds every vertex among the diced ones.
  std::vector<PolygonMesh> coarse_meshes;
  TJunctionStats coarse_seams;
  if (s.config.lighting.grid > 0.0) {
    coarse_meshes.reserve(to_emit.size());
    for (std::size_t i = 0; i < to_emit.size(); ++i)
      coarse_meshes.push_back(dice_size(s, *to_emit[i].first) > 0.0 ? mesh_polygon(*to_emit[i].first, 0.0)
                                                                    : meshes[i]);
    coarse_seams = repair_t_junctions(coarse_meshes, s.weld_tolerance);
  }
  for (std::size_t i = 0; i < to_emit.size(); ++i)
    emit(s, *to_emit[i].first, to_emit[i].second, meshes[i],
         coarse_meshes.empty() ? meshes[i] : coarse_meshes[i], diced.empty() ? meshes[i] : diced[i],
         refined_direct_ ? &direct[i] : nullptr);
  add_polygon_textures(s.model, emitted_, out);
  return StageOutcome::ran(
      s.model.polygons.size() + panels.size(), out.polygons.size(),
      fmt::format(
          "{} vertices {} triangles grid {} m; light refinement {} of {} edges split ({} along hung "
          "panels' outlines) in {} levels ({} shadow rays); coarse {} triangles ({} polygons kept diced); "
          "T-junctions {} vertices ({} across creases) into {} triangles, {} left whole (a piece would "
          "fold) (coarse {} into {}, {} left unrepaired); "
          "textures {} ({} MiB)",
          out.vertices.size(), out.indices.size() / 3, s.config.lighting.grid, refined.edges_split,
          refined.edges_tested, refined.outline_splits, refined.levels, refined.shadow_rays,
          out.coarse_indices.size() / 3, coarse_fallbacks_, seams.vertices_inserted,
          seams.crease_vertices_inserted, seams.triangles_split, seams.splits_refused,
          coarse_seams.vertices_inserted, coarse_seams.triangles_split, coarse_unrepaired_,
          out.textures.size(), out.texels.size() >> 20));
}

}  // namespace

std::unique_ptr<Stage> mesh_stage() {
  return std::make_unique<MeshStage>();
}

}  // namespace walk::compiler
