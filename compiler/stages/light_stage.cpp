// light: light per vertex and circuit, by progressive radiosity (shooting rays from each circuit's
// luminaires and then from the brightest patches) or by direct light alone. Its inputs are hashed: a compile
// that changed nothing the solve reads (only exposure, ambient or visibility knobs, say) keeps the previous
// bundle's solution.
#include <spdlog/fmt/fmt.h>

#include <cstddef>
#include <numbers>

#include "common/hash.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "compiler/radiosity/vertex_light.hpp"
#include "compiler/stages/stages.hpp"

namespace walk::compiler {
namespace {

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
    const double knobs[] = {double(l.method), l.grid,     double(l.samples_per_luminaire),
                            l.rays_per_watt,  l.residual, double(s.model.circuits.size())};
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
    const std::size_t circuits = s.model.circuits.size();
    out.light.assign(out.vertices.size() * circuits * 3, 0.0f);
    if (s.model.luminaires.empty())
      return StageOutcome::skipped("no luminaires: display shows ambient light only");
    const model::StageRecord* before = previous_record(s, "light");
    if (before && before->input_hash == input_hash && before->ran != 0 &&
        s.previous->light().size() == out.light.size()) {
      out.light.assign(s.previous->light().begin(), s.previous->light().end());
      out.polygon_light.assign(s.previous->polygon_light().begin(), s.previous->polygon_light().end());
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
    const RadiosityResult r = solve_radiosity(s.patches, emitters, points, circuits, ro);
    out.light = vertex_radiosity(s.patches, r);
    out.polygon_light = polygon_radiosity(s.patches, r, out.polygons.size());
    const auto& st = r.stats;
    return StageOutcome::ran(
        s.patches.patches.size(), st.rays,
        fmt::format("radiosity: {} patches, {} circuits, {} rays in {} shots / {} rounds, {:.2f} Mrays/s, "
                    "residual {:.2f}%, absorbed {:.1f} W escaped {:.1f} W of {:.1f} W",
                    s.patches.patches.size(), circuits, st.rays, st.shots, st.rounds,
                    st.rays / st.seconds * 1e-6, 100.0 * st.unshot / st.emitted, st.absorbed, st.escaped,
                    st.emitted));
  }

  static StageOutcome direct(CompileState& s) {
    auto& out = s.out;
    const std::size_t circuits = s.model.circuits.size();
    const TriangleBvh bvh(std::move(s.occluders));
    DirectLightStats st;
    const auto light = direct_light(s.samples, s.model.luminaires, circuits, bvh,
                                    {s.config.lighting.samples_per_luminaire, s.options.threads}, &st);
    for (std::size_t i = 0; i < s.samples.size(); ++i)
      std::copy_n(&light[i * circuits * 3], circuits * 3, &out.light[s.sample_vertex[i] * circuits * 3]);
    // Panels glow with their exitance Phi/A in their own circuit.
    for (const auto& [polygon, luminaire] : s.panel_polygons) {
      const auto& poly = out.polygons[polygon];
      const auto& l = out.luminaires[luminaire];
      for (std::uint32_t v = poly.first_vertex; v < poly.first_vertex + poly.vertex_count; ++v)
        for (int c = 0; c < 3; ++c)
          out.light[(v * circuits + l.circuit) * 3 + c] = l.power[c] / (l.width * l.height);
    }
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
