// meta: the bundle's header (origin, bounds, scene hash, exposure) and its material, group and circuit
// tables. Automatic exposure maps the 95th percentile of lit-surface radiosity to 80 % of white.
#include <spdlog/fmt/fmt.h>

#include <algorithm>

#include "compiler/stages/stages.hpp"
#include "model/version.hpp"

namespace walk::compiler {
namespace {

// Automatic exposure maps this percentile of lit-surface radiosity to 1/kExposureHeadroom of white.
constexpr double kExposurePercentile = 0.95;
constexpr double kExposureHeadroom = 0.8;

float automatic_exposure(const CompileState& s) {
  std::vector<float> totals;
  for (std::size_t i = 0; i < s.samples.size() && !s.out.light.empty(); ++i) {
    float sum = 0.0f;
    for (const model::LightEntry& e : s.out.light.row(s.sample_vertex[i]))
      for (const float b : e.rgb) sum += b;
    if (sum > 0.0f) totals.push_back(sum / 3.0f);
  }
  float exposure = 1.0f;
  if (!totals.empty()) {
    auto nth = totals.begin() + static_cast<std::ptrdiff_t>(kExposurePercentile * (totals.size() - 1));
    std::nth_element(totals.begin(), nth, totals.end());
    exposure = static_cast<float>(*nth / kExposureHeadroom);
  }
  return std::max(exposure, 1e-6f);
}

class MetaStage final : public Stage {
 public:
  const char* name() const override { return "meta"; }
  StageOutcome run(CompileState& s, std::uint64_t) override {
    auto& out = s.out;
    const auto& model = s.model;
    const std::size_t circuits = model.circuits.size();
    model::Bounds local;
    for (const auto& v : out.vertices) local.add({v.position[0], v.position[1], v.position[2]});
    auto& meta = out.meta;
    for (int a = 0; a < 3; ++a) {
      meta.origin[a] = model.origin[a];
      meta.bounds_min[a] = static_cast<float>(local.min[a]);
      meta.bounds_max[a] = static_cast<float>(local.max[a]);
    }
    meta.ambient = static_cast<float>(s.config.lighting.ambient);
    meta.scene_hash = scene_hash(s.config);
    meta.circuit_count = static_cast<std::uint32_t>(circuits);
    meta.compiler_version = out.add_string(std::string("walk ") + version());
    meta.exposure =
        s.config.lighting.exposure ? static_cast<float>(*s.config.lighting.exposure) : automatic_exposure(s);
    for (const auto& m : model.materials)
      out.materials.push_back(
          {{float(m.reflectance.r), float(m.reflectance.g), float(m.reflectance.b)}, out.add_string(m.name)});
    for (const auto& g : model.groups) out.groups.push_back({out.add_string(g)});
    for (std::size_t c = 0; c < circuits; ++c) {
      model::CircuitRecord r{out.add_string(model.circuits[c].name), float(model.circuits[c].default_level)};
      if (!s.compact.scale.empty()) {
        r.compact_scale = s.compact.scale[c];
        r.light_form = s.compact.compact[c] ? model::LightForm::Compact : model::LightForm::Full;
        r.compact_error = static_cast<float>(s.compact.circuit_rms[c]);
      }
      out.circuits.push_back(r);
    }
    return StageOutcome::ran(model.materials.size() + model.groups.size() + circuits,
                             out.materials.size() + out.groups.size() + out.circuits.size(),
                             fmt::format("exposure {:.4g}{}, {} materials, {} groups, {} circuits",
                                         meta.exposure, s.config.lighting.exposure ? "" : " (automatic)",
                                         out.materials.size(), out.groups.size(), out.circuits.size()));
  }
};

}  // namespace

std::unique_ptr<Stage> meta_stage() {
  return std::make_unique<MetaStage>();
}

}  // namespace walk::compiler
