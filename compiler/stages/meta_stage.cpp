// meta: the bundle's header (origin, bounds, scene hash, exposure) and its material, group and circuit
// tables. Automatic exposure maps the 95th percentile (by area) of lit-surface radiosity to 80 % of white.
#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <vector>

#include "compiler/lighting/auto_exposure.hpp"
#include "compiler/stages/stages.hpp"
#include "model/version.hpp"

namespace walk::compiler {
namespace {

// Automatic exposure maps this percentile of lit-surface radiosity to 1/kExposureHeadroom of white.
constexpr double kExposurePercentile = 0.95;
constexpr double kExposureHeadroom = 0.8;

// Over the lit vertices, each weighted by a third of the area of the triangles it is a corner of.
float automatic_exposure(const CompileState& s) {
  if (s.out.light.empty()) return 1.0f;
  const auto& vertices = s.out.vertices;
  std::vector<double> area(vertices.size(), 0.0);
  const auto& idx = s.out.indices;
  for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
    if (std::max({idx[k], idx[k + 1], idx[k + 2]}) >= vertices.size()) continue;
    const auto& a = vertices[idx[k]].position;
    const auto& b = vertices[idx[k + 1]].position;
    const auto& c = vertices[idx[k + 2]].position;
    const model::Vec3 ab(b[0] - a[0], b[1] - a[1], b[2] - a[2]), ac(c[0] - a[0], c[1] - a[1], c[2] - a[2]);
    const double third = glm::length(glm::cross(ab, ac)) / 6.0;
    for (int j = 0; j < 3; ++j) area[idx[k + j]] += third;
  }
  std::vector<double> totals, weights;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const std::uint32_t v = s.sample_vertex[i];
    double sum = 0.0;
    for (const model::LightEntry& e : s.out.light.row(v))
      for (const float b : e.rgb) sum += b;
    if (sum > 0.0 && v < area.size()) {
      totals.push_back(sum / 3.0);
      weights.push_back(area[v]);
    }
  }
  const double at = weighted_percentile(totals, weights, kExposurePercentile);
  return std::max(static_cast<float>(at / kExposureHeadroom), 1e-6f);
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
