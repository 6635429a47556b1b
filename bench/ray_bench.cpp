// Google Benchmark: closest and any-hit rays per backend on the house and the generated tower (the CSV sweep
// with all models and thread counts is `walk bench rays`), and the watertight triangle test alone.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "compiler/raycast/embree_caster.hpp"
#include "compiler/raycast/ray_caster.hpp"
#include "compiler/raycast/watertight_triangle.hpp"
#include "tools/bench_support/ray_models.hpp"
#include "tools/bench_support/ray_sets.hpp"

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

// The exact test alone: random rays against random small triangles in a unit cube, nearly all misses (as
// in a BSP leaf). Its branches decide the speed: the signs of a miss are unpredictable.
void watertight_triangle(benchmark::State& state) {
  using walk::model::Vec3;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  std::vector<walk::compiler::Triangle> tris;
  for (int i = 0; i < 4096; ++i) {
    const Vec3 p = point();
    tris.push_back({p, p + 0.3 * point(), p + 0.3 * point(), 0});
  }
  std::vector<walk::compiler::ShearedRay> rays;
  for (int i = 0; i < 64; ++i) rays.emplace_back(point(), point());
  std::size_t r = 0, hits = 0;
  for (auto _ : state) {
    for (const auto& t : tris) {
      double th = 0.0;
      hits += walk::compiler::intersect_watertight(rays[r], t.a, t.b, t.c, 0.0, 1e30, th) ? 1 : 0;
    }
    r = (r + 1) % rays.size();
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(tris.size()));
}

int register_all() {
  benchmark::RegisterBenchmark("watertight_triangle/random", watertight_triangle);
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
