// walk bench radiosity: what radiosity accuracy costs in time. Sweeps patch size and rays per watt on the
// measured Cornell box and the sample house, printing seconds, rays and the error of what the display shows
// (vertex-interpolated radiosity at fixed probe points) against a converged fine solution, as CSV; optionally
// plots error against seconds with gnuplot. A last row times a church-scale solve (27k+ patches).
#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "compiler/pipeline.hpp"
#include "compiler/radiosity/validation/cornell_box.hpp"
#include "compiler/radiosity/validation/display_error.hpp"
#include "compiler/radiosity/vertex_light.hpp"
#include "model/error.hpp"
#include "tools/commands.hpp"
#include "tools/gnuplot.hpp"

namespace walk::tools {
namespace bench_radiosity_command {  // named: walk compiles its commands as one unit

using compiler::ShadedMesh;

struct Run {
  ShadedMesh mesh;
  std::size_t patches = 0;
  std::uint64_t rays = 0;
  double seconds = 0.0;
};

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

Run cornell_run(const compiler::CornellBox& box, double grid, double rays_per_watt, unsigned threads) {
  std::vector<compiler::AreaEmitter> emitters;
  const compiler::PatchSet set = compiler::cornell_patches(box, grid, emitters);
  compiler::RadiosityOptions o;
  o.rays_per_watt = rays_per_watt;
  o.residual = 1e-3;
  o.threads = threads;
  const auto result = compiler::solve_radiosity(set, emitters, {}, 1, o);
  const auto light = compiler::vertex_radiosity(set, result);
  Run run{{set.vertices, {}, std::vector<std::vector<std::uint32_t>>(box.surfaces.size())},
          set.patches.size(),
          result.stats.rays,
          result.stats.seconds};
  for (std::size_t v = 0; v < set.vertices.size(); ++v) run.mesh.value.push_back(light.scalar(v));
  for (const auto& p : set.patches) {
    if (box.surfaces[p.polygon].material == "emitter") continue;  // probes only on lit surfaces
    auto& tris = run.mesh.polygon_triangles[p.polygon];
    tris.insert(tris.end(), p.v.begin(), p.v.end());
  }
  return run;
}

Run scene_run(const compiler::SceneConfig& base, double grid, double rays_per_watt, unsigned threads) {
  compiler::SceneConfig config = base;
  config.lighting.grid = grid;
  config.lighting.rays_per_watt = rays_per_watt;
  config.lighting.method = compiler::LightingMethod::Radiosity;
  const auto result = compiler::compile_scene(config, {threads});
  const auto& b = result.bundle;
  Run run;
  for (const auto& s : result.stages)
    if (s.name == "light") {
      run.seconds = s.seconds;
      run.rays = s.items_out;
      run.patches = s.items_in;
    }
  for (std::size_t v = 0; v < b.vertices.size(); ++v) {
    const auto& p = b.vertices[v].position;
    run.mesh.vertices.emplace_back(p[0], p[1], p[2]);
    double sum = 0.0;
    if (!b.light.empty())
      for (const model::LightEntry& e : b.light.row(v))
        for (const float x : e.rgb) sum += x;
    run.mesh.value.push_back(sum / 3.0);
  }
  for (const auto& poly : b.polygons) {
    run.mesh.polygon_triangles.emplace_back();
    if (poly.role == static_cast<std::uint32_t>(model::Role::Luminaire)) continue;
    run.mesh.polygon_triangles.back().assign(b.indices.begin() + poly.first_index,
                                             b.indices.begin() + poly.first_index + poly.index_count);
  }
  return run;
}

struct Sweep {
  std::string scene;
  std::vector<double> grids;
  std::vector<double> rays_per_watt;
  double reference_grid;
  double reference_rays_per_watt;
  double probes_per_square_metre;
};

int run_bench(const std::string& which, bool quick, unsigned threads, const std::string& plot,
              const std::string& data_dir, const std::string& house_scene) {
  const std::string data = data_dir + "/";
  std::vector<Sweep> sweeps;
  if (which == "cornell" || which == "all")
    sweeps.push_back(quick ? Sweep{"cornell", {0.1}, {3e5, 1e6}, 0.1, 3e6, 2000}
                           : Sweep{"cornell", {0.2, 0.1, 0.05}, {1e5, 3e5, 1e6, 3e6, 1e7}, 0.05, 3e7, 4000});
  if (which == "house" || which == "all")
    sweeps.push_back(quick ? Sweep{"house", {0.8}, {100, 300}, 0.8, 1000, 20}
                           : Sweep{"house", {0.8, 0.4, 0.2}, {100, 300, 1000, 3000}, 0.2, 10000, 50});
  if (sweeps.empty()) throw Error("--scene must be cornell, house or all");

  const auto box = compiler::load_cornell_box(data + "cornell-box/cornell_box_geometry.txt",
                                              data + "cornell-box/reflectance_spectra.csv");
  const auto house = compiler::load_scene_config(house_scene);
  auto run_for = [&](const std::string& scene, double grid, double rpw) {
    return scene == "cornell" ? cornell_run(box, grid, rpw, threads) : scene_run(house, grid, rpw, threads);
  };

  std::ostringstream csv;
  csv << "scene,grid_m,rays_per_watt,patches,rays,seconds,rms_error,mean_ratio\n";
  for (const auto& sweep : sweeps) {
    const Run reference = run_for(sweep.scene, sweep.reference_grid, sweep.reference_rays_per_watt);
    const auto probes = compiler::make_probes(reference.mesh, sweep.probes_per_square_metre);
    const auto ref_values = compiler::evaluate(reference.mesh, probes);
    std::fprintf(stderr,
                 "%s: reference grid %.3g m, %.3g rays/W: %zu patches, %llu rays, %.2f s, %zu probes\n",
                 sweep.scene.c_str(), sweep.reference_grid, sweep.reference_rays_per_watt, reference.patches,
                 static_cast<unsigned long long>(reference.rays), reference.seconds, probes.size());
    for (double grid : sweep.grids) {
      for (double rpw : sweep.rays_per_watt) {
        const Run run = run_for(sweep.scene, grid, rpw);
        const auto e = compiler::compare(compiler::evaluate(run.mesh, probes), ref_values);
        csv << sweep.scene << ',' << grid << ',' << rpw << ',' << run.patches << ',' << run.rays << ','
            << run.seconds << ',' << e.rms << ',' << e.mean_ratio << '\n';
        std::cout << sweep.scene << ',' << grid << ',' << rpw << ',' << run.patches << ',' << run.rays << ','
                  << run.seconds << ',' << e.rms << ',' << e.mean_ratio << std::endl;
      }
    }
  }
  // Church scale: the paper's church had 26,794 patches and 13 circuits; the house at 0.3 m has more of both.
  if (!quick && (which == "house" || which == "all")) {
    const Run church = scene_run(house, 0.3, house.lighting.rays_per_watt, threads);
    std::fprintf(
        stderr,
        "church-scale: house at 0.3 m: %zu patches, 16 circuits, residual %.0f%%: %.2f s, %llu rays, %.2f "
        "Mrays/s, peak RSS %.0f MiB\n",
        church.patches, 100.0 * house.lighting.residual, church.seconds,
        static_cast<unsigned long long>(church.rays), church.rays / church.seconds * 1e-6, peak_rss_mib());
  }
  if (!plot.empty()) {
    // Each grid of each scene is one line of error against solve time (log-log).
    std::ostringstream commands;
    commands << "set logscale xy\nset key outside\nset xlabel 'solve seconds'\n"
             << "set ylabel 'display RMS error (fraction of mean)'\n"
             << "set title 'Radiosity accuracy against time (walk bench radiosity)'\nplot ";
    bool first = true;
    for (const auto& sweep : sweeps)
      for (double grid : sweep.grids) {
        commands << (first ? "" : ", ") << "'" << plot_data_path(plot) << "' using ((strcol(1) eq '"
                 << sweep.scene << "' && abs($2 - " << grid
                 << ") < 1e-9) ? $6 : 1/0):7 with linespoints title '" << sweep.scene << " " << grid << " m'";
        first = false;
      }
    commands << "\n";
    plot_with_gnuplot(plot, csv.str(), commands.str());
  }
  return 0;
}

}  // namespace bench_radiosity_command

void add_bench_radiosity_command(CLI::App& bench, int& exit_code) {
  using namespace bench_radiosity_command;
  struct Args {
    std::string scene = "all", plot;
    // Defaults point into the source tree this binary was built from (a developer tool, not installed).
    std::string data = std::string(WALK_SOURCE_DIR) + "/../shared/data";
    std::string house = std::string(WALK_SOURCE_DIR) + "/config/scenes/house.toml";
    bool quick = false;
    unsigned threads = 2;
  };
  auto args = std::make_shared<Args>();
  auto* cmd =
      bench.add_subcommand("radiosity", "Patch size x rays per watt sweep: seconds, rays, RMS error (CSV)");
  cmd->add_option("--scene", args->scene, "cornell, house or all");
  cmd->add_flag("--quick", args->quick, "A small sweep (for CI smoke tests)");
  cmd->add_option("-j,--threads", args->threads, "Worker threads");
  cmd->add_option("--plot", args->plot, "Also write this PNG (and its CSV beside it) with gnuplot");
  cmd->add_option("--data", args->data, "Folder of the shared data (holds cornell-box/)");
  cmd->add_option("--house", args->house, "Scene config of the building to sweep");
  cmd->callback([args, &exit_code] {
    exit_code = run_bench(args->scene, args->quick, args->threads, args->plot, args->data, args->house);
  });
}

}  // namespace walk::tools
