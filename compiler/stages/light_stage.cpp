// light: light per vertex and circuit, by progressive radiosity (shooting rays from each circuit's
// luminaires and then from the brightest patches) or by direct light alone. Its inputs are hashed: a compile
// that changed nothing the solve reads (only exposure, ambient or visibility knobs, say) keeps the previous
// bundle's solution.
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <limits>
#include <memory>
#include <numbers>
#include <span>

#include "common/hash.hpp"
#include "common/parallel_for.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/lighting/final_gather.hpp"
#include "compiler/lighting/hidden_vertices.hpp"
#include "compiler/lighting/interpolation_check.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "compiler/radiosity/refined_patches.hpp"
#include "compiler/radiosity/vertex_light.hpp"
#include "compiler/raycast/ray_caster.hpp"
#include "compiler/scene/work_budget.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

// Rays of a target's pilot solve's first round: enough hits for a stable estimate on any shipped scene,
// a few percent of a real solve's rays.
constexpr double kPilotRays = 2e5;
// The estimate falls a little slower than 1/sqrt(rays) (emitted light has no noise, and rarely hit patches
// join the sum as rays grow): 20 % more rays than the square law asks.
constexpr double kTargetMargin = 1.2;
// A solve whose estimate is within this factor of the target is kept; beyond it one more solve is run.
constexpr double kTargetSlack = 1.15;
// The final gather's relative error where the scene gives no target: the shipped scenes' usual target.
constexpr double kDefaultGatherError = 0.05;
// The interpolation checks' draw of triangles: fixed, so a compile is repeatable.
constexpr std::uint64_t kInterpolationSeed = 0x5eed;

template <typename T>
std::uint64_t hash_vector(std::uint64_t h, const std::vector<T>& v) {
  return hash_bytes(h, v.data(), v.size() * sizeof(T));
}

class LightStage final : public Stage {
 public:
  const char* name() const override { return "light"; }

  // The solve depends only on the meshed surfaces, their reflectances, the luminaires and the lighting
  // knobs: hashing exactly these lets a compile that changed anything else reuse it.
  std::uint64_t input_hash(const CompileState& s) const override {
    const auto& out = s.out;
    const auto& l = s.config.lighting;
    std::uint64_t h = compiler_identity();
    h = hash_vector(h, out.vertices);
    h = hash_vector(h, out.indices);
    for (const auto& p : out.polygons)
      h = hash_bytes(h, &p, offsetof(model::PolygonRecord, name));  // not the name
    for (const auto& r : out.luminaires) h = hash_bytes(h, &r, offsetof(model::LuminaireRecord, name));
    const double knobs[] = {double(l.method),
                            l.grid,
                            double(l.samples_per_luminaire),
                            l.rays_per_watt,
                            l.residual,
                            double(s.model.circuits.size()),
                            l.target_error.value_or(0.0),
                            double(l.gather_direct),
                            double(l.gather_indirect)};
    h = hash_bytes(h, knobs, sizeof knobs);
    for (const auto& lum : s.model.luminaires) {  // what the bundle's records leave out
      const double shape[] = {double(lum.kind), lum.cone,       lum.exponent,
                              lum.position.x,   lum.position.y, lum.position.z};
      h = hash_bytes(h, shape, sizeof shape);
      if (lum.distribution) h = hash_bytes(h ^ lum.distribution->hash(), &lum.u_axis, sizeof lum.u_axis);
    }
    return hash_bytes(h, l.ray_caster.data(), l.ray_caster.size());
  }

  StageOutcome run(CompileState& s, std::uint64_t input_hash) override {
    auto& out = s.out;
    out.light = {};
    out.polygon_light = {};
    if (s.model.luminaires.empty())
      return StageOutcome::skipped("no luminaires: display shows ambient light only");
    const model::StageRecord* before = previous_record(s, "light");
    if (before && before->input_hash == input_hash && before->ran != 0 &&
        s.previous->light().rows() == out.vertices.size()) {
      const auto light = s.previous->light(), polygon_light = s.previous->polygon_light();
      out.light = {{light.first.begin(), light.first.end()}, {light.entries.begin(), light.entries.end()}};
      out.polygon_light = {{polygon_light.first.begin(), polygon_light.first.end()},
                           {polygon_light.entries.begin(), polygon_light.entries.end()}};
      return StageOutcome::reused("surfaces, materials, luminaires and lighting knobs unchanged since " +
                                  s.previous->path());
    }
    return s.config.lighting.method == LightingMethod::Radiosity ? radiosity(s) : direct(s);
  }

 private:
  static StageOutcome radiosity(CompileState& s) {
    auto& out = s.out;
    const auto& model = s.model;
    const std::size_t circuits = model.circuits.size();
    std::vector<AreaEmitter> emitters;
    for (std::uint32_t p = 0; p < s.patches.patches.size(); ++p) {
      for (const auto& [polygon, luminaire] : s.panel_polygons) {
        if (s.patches.patches[p].polygon != polygon) continue;
        const auto& l = model.luminaires[luminaire];
        emitters.push_back({p, l.circuit, l.power / (l.width * l.height)});
      }
    }
    std::vector<PointEmitter> points;
    for (const auto& l : model.luminaires) {
      if (l.kind == model::LuminaireKind::Area) continue;
      std::shared_ptr<const EmissionSampler> sampler;
      if (l.kind == model::LuminaireKind::Photometric && l.distribution)
        sampler = std::make_shared<const EmissionSampler>(*l.distribution, PhotometricFrame(l));
      points.push_back(
          {l.position, l.normal, l.kind == model::LuminaireKind::Spot ? l.cone : std::numbers::pi,
           l.kind == model::LuminaireKind::Spot ? l.exponent : 0.0, l.power, l.circuit, std::move(sampler)});
    }
    RadiosityOptions ro;
    ro.rays_per_watt = s.config.lighting.rays_per_watt;
    ro.residual = s.config.lighting.residual;
    ro.threads = s.options.threads;
    ro.caster = s.config.lighting.ray_caster;
    std::string how = fmt::format("{:g} rays/W", ro.rays_per_watt);
    // Gathered direct light. On refined meshes: per vertex as the display shows it, per patch (the area
    // mean over the display's triangles on it) as the light the solver shoots on. Otherwise at each patch's
    // centroid, shown like shot light (the area mean of the patches around a vertex): a vertex where a wall
    // meets the floor, or just above a lamp's plane, is dark, and interpolating from it would darken the
    // light around it.
    SparseLight vertex_direct, patch_direct;
    DirectLightStats direct_stats;
    std::string direct_note;
    const bool final_gather = s.config.lighting.gather_direct && s.config.lighting.gather_indirect;
    // The light between vertices is checked against light gathered at random points of the lit triangles,
    // whichever way the light was made (interpolation_check.hpp).
    const InterpolationChecks checks =
        pick_interpolation_checks(s.samples, s.sample_vertex, s.patches.vertices, s.out.indices,
                                  std::min(kInterpolationChecks, s.samples.size()), kInterpolationSeed);
    SparseLight check_direct;
    // Refined display triangles find the patches they lie on through one locator.
    std::unique_ptr<PatchLocator> locator;
    if (s.patches_coarser_than_display) locator = std::make_unique<PatchLocator>(s.patches);
    if (s.config.lighting.gather_direct && (s.patches_coarser_than_display || final_gather)) {
      std::size_t from_refinement = 0;
      vertex_direct = gather_vertex_direct(s, &direct_stats, from_refinement, checks.points, &check_direct);
      patch_direct = patch_means(s, locator.get(), vertex_direct);
      ro.gathered_direct = &patch_direct;
      direct_note =
          fmt::format("direct gathered at vertices ({} from the light refinement, {} shadow rays), ",
                      from_refinement, direct_stats.shadow_rays);
    } else if (s.config.lighting.gather_direct) {
      patch_direct = gather_patch_direct(s, &direct_stats, checks.points, &check_direct);
      ro.gathered_direct = &patch_direct;
      direct_note = fmt::format("direct gathered ({} shadow rays), ", direct_stats.shadow_rays);
    } else {
      (void)gather_direct(s, {}, {}, 0, nullptr, checks.points, &check_direct);
    }
    // One caster over the patches serves every solve (a target's pilot and real solves), the final gather
    // and the interpolation checks.
    const auto caster = make_ray_caster(ro.caster, s.patches.triangles());
    ro.built_caster = caster.get();
    RadiosityResult r =
        s.config.lighting.target_error
            ? solve_to_target(s, emitters, points, circuits, ro, *s.config.lighting.target_error, how)
            : solve_radiosity(s.patches, emitters, points, circuits, ro);
    out.polygon_light = polygon_radiosity(s.patches, r, out.polygons.size());
    FinalGatherStats gathered, checked;
    SparseLight indirect, check_indirect;
    if (!checks.points.empty() || final_gather) {
      const FinalGatherOptions o = final_gather_options(s);
      const SparseLight outgoing = outgoing_light(emitters, r);
      if (final_gather) {
        indirect = gather_indirect_at_vertices(s, *caster, outgoing, vertex_direct, o, &gathered);
        direct_note += fmt::format(
            "indirect gathered at vertices ({} rays, estimated {:.2f}%, {} at the cap, {:.0f}% of the "
            "light), ",
            gathered.rays, 100.0 * gathered.estimated_error, gathered.capped,
            100.0 * gathered.gathered_share);
      }
      std::vector<double> check_shown(checks.points.size());
      for (std::size_t k = 0; k < check_shown.size(); ++k) check_shown[k] = check_direct.scalar(k);
      check_indirect = gather_indirect(*caster, outgoing, checks.points, check_shown, o, &checked);
    }
    SparseLight light;
    if (!vertex_direct.empty()) {
      // The display: the direct light as gathered at its vertex plus the patches' shot light around it.
      for (std::size_t i = 0; i < patch_direct.rows(); ++i) r.radiosity.add(i, patch_direct.row(i), -1.0);
      light = vertex_radiosity(s.patches, r);
      if (final_gather) {
        // Every lit vertex shows what it gathered, so the shot light around it is not spread to it; the
        // panels (no samples) keep their patches' glow.
        for (std::size_t i = 0; i < s.samples.size(); ++i) {
          const std::uint32_t v = s.sample_vertex[i];
          light.set_row(v, vertex_direct.row(v));
          light.add(v, indirect.row(i));
        }
        const std::size_t shown_as_neighbours =
            show_hidden_as_neighbours(s.out.indices, s.sample_vertex, gathered.hidden, light);
        direct_note +=
            fmt::format("{} vertices no view sees shown as their neighbours, ", shown_as_neighbours);
      } else {
        if (s.patches_coarser_than_display) {
          const std::size_t lost = spread_to_refined_vertices(s, *locator, light);
          direct_note +=
              fmt::format("shot light spread to refined vertices ({} off patches: nearest corner), ", lost);
        }
        for (std::size_t i = 0; i < vertex_direct.rows(); ++i) light.add(i, vertex_direct.row(i));
      }
    } else {
      light = vertex_radiosity(s.patches, r);
    }
    // What a view sees against the gathered truth: with the final gather both carry the gather's noise,
    // which is taken out of both; otherwise the shown light's shooting noise is error a view sees, and only
    // the truth's is taken out.
    double interpolation = 0.0;
    if (!checks.points.empty()) {
      std::vector<double> truth(checks.points.size());
      for (std::size_t k = 0; k < truth.size(); ++k)
        truth[k] = check_direct.scalar(k) + check_indirect.scalar(k);
      interpolation = interpolation_error(checks, light, truth, checked.estimated_error,
                                          final_gather ? gathered.estimated_error : 0.0, checked.hidden);
      const auto target = s.config.lighting.target_error;
      if (target && interpolation > *target * kTargetSlack)
        spdlog::warn(
            "{}: the light between vertices is {:.1f}% off, above [lighting] target_error = {:g}: more rays "
            "will not mend it; direct = \"gather\" with refine = true meshes where the light bends, and "
            "indirect = \"gather\" reads it at every vertex (or set a finer grid)",
            s.config.path, 100.0 * interpolation, *target);
      const auto hidden = std::count(checked.hidden.begin(), checked.hidden.end(), 1);
      direct_note += fmt::format("between vertices {:.2f}% at {} points in triangles ({} hidden; {} rays), ",
                                 100.0 * interpolation, checks.points.size(), hidden, checked.rays);
    }
    out.light = light.to_rows();
    const auto& st = r.stats;
    auto outcome = StageOutcome::ran(
        s.patches.patches.size(), st.rays + gathered.rays + checked.rays,
        fmt::format(
            "radiosity: {}, estimated error {:.2f}%; {} patches, {} circuits, {} rays in {} shots / {} "
            "rounds, {:.2f} Mrays/s, residual {:.2f}%, absorbed {:.1f} W escaped {:.1f} W of {:.1f} W shot",
            direct_note + how, 100.0 * st.estimated_error, s.patches.patches.size(), circuits, st.rays,
            st.shots, st.rounds, st.rays / st.seconds * 1e-6, 100.0 * st.unshot / st.emitted, st.absorbed,
            st.escaped, st.emitted));
    // With a final gather the shown light's noise is the gather's and the patches' shooting noise in the
    // share of it that was gathered (an upper bound: a vertex averages it over every patch it sees), and
    // its error between vertices is measured apart. Without it, the check measured the shooting noise too.
    outcome.estimated_error =
        final_gather
            ? std::hypot(std::hypot(gathered.estimated_error, gathered.gathered_share * st.estimated_error),
                         interpolation)
            : std::max(st.estimated_error, interpolation);
    return outcome;
  }

  // Each patch's radiosity less its own emission: what the final gather reads off the patches (panels' glow
  // reaches the vertices as their gathered direct light).
  static SparseLight outgoing_light(std::span<const AreaEmitter> emitters, const RadiosityResult& r) {
    SparseLight outgoing = r.radiosity;
    for (const AreaEmitter& e : emitters) {
      double* b = outgoing.at(e.patch, e.circuit);
      for (int c = 0; c < 3; ++c) b[c] = std::max(0.0, b[c] - e.exitance[c]);
    }
    return outgoing;
  }

  static FinalGatherOptions final_gather_options(const CompileState& s) {
    FinalGatherOptions o;
    o.target_error = s.config.lighting.target_error.value_or(kDefaultGatherError);
    o.threads = s.options.threads;
    o.caster = s.config.lighting.ray_caster;
    return o;
  }

  // Indirect light at every lit vertex, gathered from the solved patches through `caster` (over
  // `s.patches.triangles()`).
  static SparseLight gather_indirect_at_vertices(const CompileState& s, const RayCaster& caster,
                                                 const SparseLight& outgoing,
                                                 const SparseLight& vertex_direct,
                                                 const FinalGatherOptions& o, FinalGatherStats* stats) {
    std::vector<double> shown_direct;
    shown_direct.reserve(s.samples.size());
    for (const std::uint32_t v : s.sample_vertex) shown_direct.push_back(vertex_direct.scalar(v));
    std::vector<SurfaceSample> receivers = s.samples;
    inset_from_edges(receivers, s.sample_vertex, s.patches.vertices, s.out.indices);
    return gather_indirect(caster, outgoing, receivers, shown_direct, o, stats);
  }

  // Direct light gathered at `samples` against the scene's shadow occluders (consumed: a compile gathers
  // once), written at row index[i] of `count` rows; rows no sample lands on stay empty. With `extra_light`,
  // also at `extra`, a row each.
  static SparseLight gather_direct(CompileState& s, std::span<const SurfaceSample> samples,
                                   std::span<const std::uint32_t> index, std::size_t count,
                                   DirectLightStats* stats, std::span<const SurfaceSample> extra = {},
                                   SparseLight* extra_light = nullptr) {
    const TriangleBvh bvh(std::move(s.occluders));
    const DirectLightOptions options{s.config.lighting.samples_per_luminaire, s.options.threads};
    if (extra_light)
      *extra_light = direct_light(extra, s.model.luminaires, s.model.circuits.size(), bvh, options);
    const auto light =
        direct_light(samples, s.model.luminaires, s.model.circuits.size(), bvh, options, stats);
    SparseLight out(count);
    for (std::size_t i = 0; i < samples.size(); ++i) out.set_row(index[i], light.row(i));
    return out;
  }

  // Direct light at every lit vertex (panels glow, so their rows stay empty), a row per vertex: the light
  // refinement's where it gathered it (the values its edges were tested with), gathered here for the rest.
  // `refined`: how many vertices took the refinement's.
  // With `extra_light`, also at `extra`, a row each.
  static SparseLight gather_vertex_direct(CompileState& s, DirectLightStats* stats, std::size_t& refined,
                                          std::span<const SurfaceSample> extra = {},
                                          SparseLight* extra_light = nullptr) {
    refined = 0;
    if (s.sample_refined.empty())
      return gather_direct(s, s.samples, s.sample_vertex, s.out.vertices.size(), stats, extra, extra_light);
    std::vector<SurfaceSample> rest;
    std::vector<std::uint32_t> rest_vertex;
    for (std::size_t i = 0; i < s.samples.size(); ++i)
      if (!s.sample_refined[i]) {
        rest.push_back(s.samples[i]);
        rest_vertex.push_back(s.sample_vertex[i]);
      }
    auto out = gather_direct(s, rest, rest_vertex, s.out.vertices.size(), stats, extra, extra_light);
    for (std::size_t i = 0; i < s.samples.size(); ++i) {
      if (!s.sample_refined[i]) continue;
      ++refined;
      out.set_row(s.sample_vertex[i], s.sample_direct.row(i));
      for (CircuitLight& e : out.row(s.sample_vertex[i]))
        for (int c = 0; c < 3; ++c) e.rgb[c] *= s.samples[i].albedo[c];
    }
    return out;
  }

  // Vertices the light refinement added are corners of no patch: they take the shot light interpolated
  // over the patch they lie on. Returns how many found no patch (they take their polygon's nearest corner's).
  static std::size_t spread_to_refined_vertices(const CompileState& s, const PatchLocator& locator,
                                                SparseLight& light) {
    const PatchSet& set = s.patches;
    std::vector<std::uint8_t> corner(set.vertices.size(), 0);
    for (const Patch& p : set.patches)
      for (const std::uint32_t v : p.v) corner[v] = 1;
    SparseLight filled(light);
    std::atomic<std::size_t> lost{0};
    parallel_ranges(set.vertices.size(), 1024, s.options.threads, [&](std::size_t first, std::size_t last) {
      for (std::size_t v = first; v < last; ++v) {
        if (corner[v]) continue;
        const auto& nv = s.out.vertices[v].normal;
        const auto at = locator.locate(set.vertices[v], model::Vec3(nv[0], nv[1], nv[2]));
        if (!at) {  // on a patch's edge, where the ray slipped between: the polygon's nearest corner
          ++lost;
          const auto& poly = s.out.polygons[s.out.vertices[v].polygon];
          std::size_t nearest = v;
          double best = std::numeric_limits<double>::infinity();
          for (std::size_t u = poly.first_vertex; u < poly.first_vertex + poly.vertex_count; ++u) {
            const model::Vec3 d = set.vertices[u] - set.vertices[v];
            if (corner[u] && glm::dot(d, d) < best) {
              best = glm::dot(d, d);
              nearest = u;
            }
          }
          filled.set_row(v, light.row(nearest));
          continue;
        }
        const Patch& p = set.patches[at->patch];
        filled.clear_row(v);
        for (int i = 0; i < 3; ++i) filled.add(v, light.row(p.v[i]), at->weights[i]);
      }
    });
    light = std::move(filled);
    return lost.load();
  }

  // Direct light at each patch's centroid (panels glow, so their rows stay empty), a row per patch.
  // With `extra_light`, also at `extra`, a row each.
  static SparseLight gather_patch_direct(CompileState& s, DirectLightStats* stats,
                                         std::span<const SurfaceSample> extra = {},
                                         SparseLight* extra_light = nullptr) {
    std::vector<std::uint8_t> panel(s.out.polygons.size(), 0);
    for (const auto& [polygon, luminaire] : s.panel_polygons) panel[polygon] = 1;
    std::vector<SurfaceSample> samples;
    std::vector<std::uint32_t> patch_of;
    for (std::uint32_t i = 0; i < s.patches.patches.size(); ++i) {
      const Patch& p = s.patches.patches[i];
      if (p.polygon < panel.size() && panel[p.polygon]) continue;
      const auto& v = s.patches.vertices;
      samples.push_back({(v[p.v[0]] + v[p.v[1]] + v[p.v[2]]) / 3.0, p.normal, p.reflectance});
      patch_of.push_back(i);
    }
    return gather_direct(s, samples, patch_of, s.patches.patches.size(), stats, extra, extra_light);
  }

  // The direct light each patch shoots: the mean of its corners where patches are the display's triangles,
  // else the area mean over the refined triangles on it (refined_patches.hpp).
  static SparseLight patch_means(const CompileState& s, const PatchLocator* locator,
                                 const SparseLight& per_vertex) {
    if (locator) return patch_area_means(s.patches, s.out.indices, per_vertex, *locator, s.options.threads);
    SparseLight out(s.patches.patches.size());
    for (std::size_t p = 0; p < s.patches.patches.size(); ++p)
      for (const std::uint32_t v : s.patches.patches[p].v) out.add(p, per_vertex.row(v), 1.0 / 3.0);
    return out;
  }

  // Accuracy by target: a pilot solve small enough to cost little measures the error estimate, which falls
  // as 1/sqrt(rays), and the real solve takes the rays that bring it to the target (once more if it falls
  // short by more than kTargetSlack). `how` says what was done, for the stage report.
  static RadiosityResult solve_to_target(const CompileState& s, std::span<const AreaEmitter> area,
                                         std::span<const PointEmitter> points, std::size_t circuits,
                                         RadiosityOptions ro, double target, std::string& how) {
    // The power the solver shoots: the luminaires', or with direct light gathered the light it reflects.
    double watts = 0.0;
    if (!ro.gathered_direct) {
      for (const auto& l : s.model.luminaires) watts += (l.power.r + l.power.g + l.power.b) / 3.0;
    } else {
      for (std::size_t p = 0; p < s.patches.patches.size(); ++p)
        watts += ro.gathered_direct->scalar(p) * s.patches.patches[p].area;
    }
    const double most = kMaxFirstRoundRays / std::max(watts, 1e-12);
    ro.rays_per_watt = std::min(most, kPilotRays / std::max(watts, 1e-12));
    RadiosityResult r = solve_radiosity(s.patches, area, points, circuits, ro);
    how = fmt::format("target {:.2f}%: pilot {:.3g} rays/W estimated {:.2f}%", 100.0 * target,
                      ro.rays_per_watt, 100.0 * r.stats.estimated_error);
    for (int pass = 0; pass < 2 && r.stats.estimated_error > target * (pass == 0 ? 1.0 : kTargetSlack);
         ++pass) {
      if (ro.rays_per_watt >= most) {
        spdlog::warn(
            "{}: [lighting] target_error = {:g} needs more than the {:.0e} first-round rays a compile may "
            "cast; the light is left at an estimated {:.2f}%",
            s.config.path, target, kMaxFirstRoundRays, 100.0 * r.stats.estimated_error);
        break;
      }
      const double ratio = r.stats.estimated_error / target;
      ro.rays_per_watt = std::min(most, ro.rays_per_watt * ratio * ratio * kTargetMargin);
      r = solve_radiosity(s.patches, area, points, circuits, ro);
      how += fmt::format(" -> {:.3g} rays/W", ro.rays_per_watt);
    }
    return r;
  }

  static StageOutcome direct(CompileState& s) {
    auto& out = s.out;
    const std::size_t circuits = s.model.circuits.size();
    DirectLightStats st;
    SparseLight light = gather_direct(s, s.samples, s.sample_vertex, out.vertices.size(), &st);
    // Panels glow with their exitance Phi/A in their own circuit.
    for (const auto& [polygon, luminaire] : s.panel_polygons) {
      const auto& poly = out.polygons[polygon];
      const auto& l = out.luminaires[luminaire];
      for (std::uint32_t v = poly.first_vertex; v < poly.first_vertex + poly.vertex_count; ++v) {
        double* b = light.at(v, l.circuit);
        for (int c = 0; c < 3; ++c) b[c] = l.power[c] / (l.width * l.height);
      }
    }
    out.light = light.to_rows();
    return StageOutcome::ran(s.samples.size(), st.shadow_rays,
                             fmt::format("direct: {} shadow rays, {} occluded, {} luminaires, {} circuits",
                                         st.shadow_rays, st.occluded, s.model.luminaires.size(), circuits));
  }
};

}  // namespace

std::unique_ptr<Stage> light_stage() {
  return std::make_unique<LightStage>();
}

}  // namespace walk::compiler
