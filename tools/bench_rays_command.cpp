// walk bench rays: our ray casters against Embree on the same ray sets, one CSV row per
// (model, caster, ray set, threads): build time, memory, Mrays/s and the ratio to Embree.
// walk bench rays --leak N: rays from inside closed boxes aimed at edges and vertices; escapes per caster.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <memory>
#include <sstream>

#include "compiler/raycast/axial_caster.hpp"
#include "compiler/raycast/ray_caster.hpp"
#include "model/error.hpp"
#include "tools/bench_support/leak_box.hpp"
#include "tools/bench_support/ray_models.hpp"
#include "tools/bench_support/ray_sets.hpp"
#include "tools/commands.hpp"

namespace walk::tools {
namespace bench_rays_command {  // named: walk compiles its commands as one unit

using compiler::Ray;
using compiler::RayCaster;
using compiler::RayHit;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Options {
  std::string models = "house,office,tower,e1m1,dm1,conference,sibenik";
  std::string casters = "axial,embree";
  std::string threads = "1,2";
  std::string sets = "primary,radiosity,occlusion";
  std::size_t rays = 1000000;
  std::size_t repeat = 1;
  std::size_t leak = 0;
  std::string data;
};

// Casts `rays` and returns seconds; closest hits for primary and radiosity sets, any-hit for occlusion.
double cast(const RayCaster& c, const std::vector<Ray>& rays, bool any, unsigned threads, std::size_t& hits) {
  std::vector<RayHit> h(any ? 0 : rays.size());
  std::vector<std::uint8_t> o(any ? rays.size() : 0);
  const auto t0 = Clock::now();
  if (any)
    c.occluded_batch(rays, o, threads);
  else
    c.closest_batch(rays, h, threads);
  const double s = since(t0);
  hits = 0;
  for (const auto& x : h) hits += x.hit() ? 1 : 0;
  for (const auto x : o) hits += x;
  return s;
}

std::string structure_detail(const RayCaster& c) {
  const auto* a = dynamic_cast<const compiler::AxialCaster*>(&c);
  if (!a) return "";
  const auto& p = a->planes().stats();
  const auto& b = a->bsp().stats();
  const auto& k = a->planes().blocks().stats();
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "axial %zu tris in %zu+%zu+%zu planes (%zu rects) over %zux%zux%zu blocks (%zu empty, %zu holding BSP "
      "tris) with %zu listings (%s, %zu blocks of %u-%u, mean free path %.1f m); bsp %zu tris %zu nodes (%zu "
      "axial splits) depth %d",
      p.triangles, p.planes[0], p.planes[1], p.planes[2], p.rectangles, k.blocks[0], k.blocks[1], k.blocks[2],
      k.empty, k.marked, k.entries, a->planes().blocks().uses_lanes() ? "avx-512 lanes" : "scalar merge",
      k.gathered_big, compiler::kGathered + 1, compiler::kGatheredMax, k.mean_free_path, b.triangles, b.nodes,
      b.axis_splits, b.depth);
  return buf;
}

// A caster by name; "axial@B" is the axial structure with B blocks per element and no limit from the plane
// count (for the block-size sweep).
std::unique_ptr<RayCaster> make_caster(const std::string& name, const std::vector<compiler::Triangle>& tris) {
  if (name == "axial-scalar")
    return std::make_unique<compiler::AxialCaster>(tris, compiler::BlockSizing{.lanes = false});
  if (!name.starts_with("axial@")) return compiler::make_ray_caster(name, tris);
  return std::make_unique<compiler::AxialCaster>(
      tris, compiler::BlockSizing{.per_element = std::stod(name.substr(6)), .planes_per_layer = 0.0});
}

int run_speed(const Options& opt) {
  const auto casters = split(opt.casters);
  std::vector<unsigned> threads;
  for (const auto& t : split(opt.threads)) threads.push_back(static_cast<unsigned>(std::stoul(t)));
  for (const auto& set : split(opt.sets))
    if (set != "primary" && set != "radiosity" && set != "occlusion")
      throw Error("walk bench rays: unknown ray set '" + set + "' (primary, radiosity, occlusion)");
  std::printf(
      "model,polygons,triangles,caster,build_s,memory_mb,set,threads,rays,seconds,mrays_s,ratio_vs_embree,"
      "hits,structure\n");
  for (const auto& name : split(opt.models)) {
    const auto model = bench::load_ray_model(name, opt.data);
    std::vector<std::pair<std::string, std::vector<Ray>>> sets;
    for (const auto& set : split(opt.sets)) {
      if (set == "primary")
        sets.emplace_back(set, bench::primary_rays(model.triangles, opt.rays, 1));
      else if (set == "radiosity")
        sets.emplace_back(set, bench::radiosity_rays(model.triangles, opt.rays, 2));
      else
        sets.emplace_back(set, bench::occlusion_rays(model.triangles, opt.rays, 3));
    }
    struct Row {
      std::string caster, set, detail;
      double build, mb, seconds;
      unsigned threads;
      std::size_t hits;
    };
    std::vector<Row> rows;
    std::vector<std::unique_ptr<RayCaster>> built;
    for (const auto& cname : casters) {
      const auto t0 = Clock::now();
      built.push_back(make_caster(cname, model.triangles));
      const double build = since(t0);
      const double mb = static_cast<double>(built.back()->memory_bytes()) / (1024.0 * 1024.0);
      for (const auto& [set, rays] : sets)
        for (const unsigned th : threads)
          rows.push_back({cname, set, structure_detail(*built.back()), build, mb, INFINITY, th, 0});
    }
    // Each repetition casts every set with every caster in turn, so that a slow spell of a noisy machine
    // falls on all of them alike; the best time of each counts.
    for (std::size_t rep = 0; rep < opt.repeat; ++rep) {
      std::size_t row = 0;
      for (std::size_t c = 0; c < casters.size(); ++c)
        for (const auto& [set, rays] : sets)
          for (const unsigned th : threads) {
            Row& r = rows[row++];
            r.seconds = std::min(r.seconds, cast(*built[c], rays, set == "occlusion", th, r.hits));
          }
    }
    std::map<std::pair<std::string, unsigned>, double> embree_rate;
    for (const auto& r : rows)
      if (r.caster == "embree") embree_rate[{r.set, r.threads}] = opt.rays / r.seconds;
    for (const auto& r : rows) {
      const double rate = opt.rays / r.seconds;
      const auto e = embree_rate.find({r.set, r.threads});
      char ratio[32] = "";
      if (e != embree_rate.end()) std::snprintf(ratio, sizeof ratio, "%.3f", rate / e->second);
      std::printf("%s,%zu,%zu,%s,%.3f,%.2f,%s,%u,%zu,%.3f,%.3f,%s,%zu,%s\n", name.c_str(), model.polygons,
                  model.triangles.size(), r.caster.c_str(), r.build, r.mb, r.set.c_str(), r.threads, opt.rays,
                  r.seconds, rate / 1e6, ratio, r.hits, r.detail.c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}

int run_leak(const Options& opt) {
  std::printf("box,caster,rays,escapes_closest,escapes_any,seconds\n");
  const glm::dmat3 tilt(
      glm::rotate(glm::rotate(glm::dmat4(1.0), 0.37, glm::dvec3(0, 0, 1)), 0.61, glm::dvec3(1, 1, 0)));
  struct Box {
    const char* name;
    bool quads, rotated;
  };
  for (const Box b : {Box{"axial_quads", true, false}, Box{"axial_triangles", false, false},
                      Box{"rotated_quads", true, true}, Box{"rotated_triangles", false, true}}) {
    const auto box = bench::leak_box(b.quads, 5, b.rotated ? tilt : glm::dmat3(1.0));
    const auto rays = bench::leak_rays(box, opt.leak, 7);
    for (const auto& cname : split(opt.casters)) {
      const auto caster = compiler::make_ray_caster(cname, box.triangles);
      std::vector<RayHit> hits(rays.size());
      std::vector<std::uint8_t> occluded(rays.size());
      const auto t0 = Clock::now();
      caster->closest_batch(rays, hits, 2);
      caster->occluded_batch(rays, occluded, 2);
      const double s = since(t0);
      std::size_t escapes = 0, any = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        escapes += hits[i].hit() ? 0 : 1;
        any += occluded[i] ? 0 : 1;
      }
      std::printf("%s,%s,%zu,%zu,%zu,%.3f\n", b.name, cname.c_str(), rays.size(), escapes, any, s);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace bench_rays_command

void add_bench_rays_command(CLI::App& bench, int& exit_code) {
  using namespace bench_rays_command;
  auto opt = std::make_shared<Options>();
  if (const char* env = std::getenv("WALK_SHARED_DATA"))
    opt->data = env;
  else
    opt->data = "../shared/data";
  auto* rays =
      bench.add_subcommand("rays", "Ray casting: ours vs Embree on primary, radiosity and occlusion rays");
  rays->add_option("--models", opt->models,
                   "Comma-separated: house, office, tower, e1m1, dm1, conference, sibenik, cornell; NAME@G "
                   "(house, office, e1m1, dm1): that model's radiosity patches on a G-metre grid, which the "
                   "solver casts against")
      ->capture_default_str();
  rays->add_option(
          "--casters", opt->casters,
          "Comma-separated: axial, bvh, brute, embree; axial-scalar: axial without the AVX-512 listing "
          "kernel; axial@B: axial with B blocks per element")
      ->capture_default_str();
  rays->add_option("--threads", opt->threads, "Comma-separated thread counts")->capture_default_str();
  rays->add_option("--rays", opt->rays, "Rays per set")->capture_default_str();
  rays->add_option("--sets", opt->sets, "Comma-separated ray sets: primary, radiosity, occlusion")
      ->capture_default_str();
  rays->add_option(
          "--repeat", opt->repeat,
          "Cast every set with every caster this many times in turn and report the best time of each")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  rays->add_option("--leak", opt->leak, "Instead: the leak test with this many rays per box");
  rays->add_option("--data", opt->data, "Shared data folder (or WALK_SHARED_DATA)")->capture_default_str();
  rays->callback([opt, &exit_code] { exit_code = opt->leak > 0 ? run_leak(*opt) : run_speed(*opt); });
}

}  // namespace walk::tools
