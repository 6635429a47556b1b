// Google Benchmark: closest and any-hit rays per backend on the house and the generated tower (the CSV sweep
// with all models and thread counts is `walk bench rays`).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "bench/support/ray_models.hpp"
#include "bench/support/ray_sets.hpp"
#include "compiler/raycast/embree_caster.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace {

using walk::compiler::Ray;
using walk::compiler::RayCaster;

struct Scene {
  std::unique_ptr<RayCaster> caster;
  std::vector<Ray> radiosity, occlusion;
};

// Built once per (model, caster) and kept for every benchmark that uses it.
const Scene& scene(const std::string& model, const std::string& caster) {
  static std::map<std::pair<std::string, std::string>, Scene> cache;
  auto& s = cache[{model, caster}];
  if (!s.caster) {
    const auto m = walk::bench::load_ray_model(model, WALK_SHARED_DATA);
    s.caster = walk::compiler::make_ray_caster(caster, m.triangles);
    s.radiosity = walk::bench::radiosity_rays(m.triangles, 1 << 16, 2);
    s.occlusion = walk::bench::occlusion_rays(m.triangles, 1 << 16, 3);
  }
  return s;
}

void closest(benchmark::State& state, const std::string& model, const std::string& caster) {
  const Scene& s = scene(model, caster);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.caster->closest(s.radiosity[i]));
    i = (i + 1) % s.radiosity.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void occluded(benchmark::State& state, const std::string& model, const std::string& caster) {
  const Scene& s = scene(model, caster);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.caster->occluded(s.occlusion[i]));
    i = (i + 1) % s.occlusion.size();
  }
  state.SetItemsProcessed(state.iterations());
}

int register_all() {
  for (const std::string model : {"house", "tower"}) {
    for (const std::string caster : {"axial", "embree"}) {
      if (caster == "embree" && !walk::compiler::embree_available()) continue;
      benchmark::RegisterBenchmark(("radiosity_closest/" + model + "/" + caster).c_str(), closest, model,
                                   caster);
      benchmark::RegisterBenchmark(("occlusion_any/" + model + "/" + caster).c_str(), occluded, model,
                                   caster);
    }
  }
  return 0;
}
const int registered = register_all();

}  // namespace

BENCHMARK_MAIN();
