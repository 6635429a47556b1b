// walk bench lighting: what light accuracy costs in time, against a reference that shares no code with the
// solver. For each scene, the light stage is run at a range of `target_error`s; the light the display shows
// at fixed surface points is compared with a converged path-traced reference (compiler/lighting/
// path_reference.hpp), and the reference itself is timed at a range of paths per point: the two ways of
// buying accuracy side by side, as CSV and a log-log plot of error against seconds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/lighting/path_reference.hpp"
#include "compiler/lighting/stored_light.hpp"
#include "compiler/pipeline.hpp"
#include "model/bundle.hpp"
#include "model/error.hpp"
#include "model/photometric_units.hpp"
#include "tools/commands.hpp"
#include "tools/gnuplot.hpp"

namespace walk::tools {
namespace bench_lighting_command {  // named: walk compiles its commands as one unit

namespace fs = std::filesystem;

struct Args {
  std::vector<std::string> scenes{std::string(WALK_SOURCE_DIR) + "/config/scenes/cornell-box-obj.toml",
                                  std::string(WALK_SOURCE_DIR) + "/config/scenes/house.toml"};
  std::vector<double> targets{0.2, 0.1, 0.05, 0.02};
  std::vector<int> paths{4, 16, 64, 256};
  // "gather": gathered, dicing as the scene says; "gather-refined" / "gather-flat": refined or not
  std::vector<std::string> direct{"gather", "shoot"};
  int points = 200;
  int worst = 0;  // print this many points with the largest errors
  int reference_paths = 4096;
  unsigned threads = 2;
  std::string plot;
};

// Relative RMS error of `values` (luminance) against the reference, the reference's own noise taken out in
// quadrature; also that noise, relative to the same scale, and the ratio of the means (a bias, not noise).
// Points the reference finds hidden are left out.
struct Error {
  double measured = 0.0, reference_noise = 0.0, mean_ratio = 0.0;
};
Error error_against(const std::vector<double>& values, const compiler::PathReference& ref) {
  double diff = 0.0, scale = 0.0, noise = 0.0, sum = 0.0, sum_ref = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (ref.hidden[i]) continue;  // inside a solid or behind a lamp: no view shows it
    const double r = model::luminance_weight(ref.radiosity[i]);
    sum += values[i];
    sum_ref += r;
    diff += (values[i] - r) * (values[i] - r);
    scale += r * r;
    noise += ref.standard_error[i] * ref.standard_error[i];
  }
  if (scale <= 0.0) return {};
  return {std::sqrt(std::max(0.0, diff - noise) / scale), std::sqrt(noise / scale), sum / sum_ref};
}

// Where the error comes from: the `count` points with the largest squared errors, on stderr beside the CSV.
void print_worst(const std::string& what, const std::vector<compiler::SurfacePoint>& points,
                 const std::vector<double>& values, const compiler::PathReference& ref, int count) {
  auto squared = [&](std::size_t i) {
    const double r = model::luminance_weight(ref.radiosity[i]);
    return ref.hidden[i] ? 0.0 : (values[i] - r) * (values[i] - r);
  };
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto x, auto y) { return squared(x) > squared(y); });
  double total = 0.0;
  for (const auto i : order) total += squared(i);
  // Ceilings, floors and walls apart: a bias one way on every ceiling shows as a mean ratio off 1.
  const char* facings[3] = {"down (ceilings)", "up (floors)", "sideways (walls)"};
  for (int f = 0; f < 3 && total > 0.0; ++f) {
    double shown = 0.0, reference = 0.0, share = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int facing = points[i].normal.z < -0.5 ? 0 : points[i].normal.z > 0.5 ? 1 : 2;
      if (ref.hidden[i] || facing != f) continue;
      shown += values[i];
      reference += model::luminance_weight(ref.radiosity[i]);
      share += squared(i) / total;
      ++n;
    }
    if (n > 0 && reference > 0.0)
      std::fprintf(stderr, "  %s, facing %s: %d points, mean ratio %.3f, %.1f%% of the squared error\n",
                   what.c_str(), facings[f], n, shown / reference, 100.0 * share);
  }
  for (std::size_t j = 0; j < std::min<std::size_t>(std::size_t(count), order.size()) && total > 0.0; ++j) {
    const auto i = order[j];
    const auto& p = points[i];
    std::fprintf(stderr,
                 "  %s: point %zu at %.2f %.2f %.2f (local m) facing %.1f %.1f %.1f: reference %.3f +- %.3f, "
                 "shown %.3f W/m2; %.1f%% of the squared error\n",
                 what.c_str(), i, p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y,
                 p.normal.z, model::luminance_weight(ref.radiosity[i]), ref.standard_error[i], values[i],
                 100.0 * squared(i) / total);
  }
}

int run(const Args& a) {
  const fs::path tmp = fs::temp_directory_path() / ("walk_bench_lighting_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  std::ostringstream csv;
  csv << "scene,method,setting,rays,seconds,estimated_error,error_vs_reference,reference_noise,mean_ratio\n";
  std::printf("%s", csv.str().c_str());
  auto row = [&](const std::string& scene, const char* method, double setting, std::uint64_t rays,
                 double seconds, double estimated, const Error& e) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%g,%llu,%.4f,%.5f,%.5f,%.5f,%.4f\n", scene.c_str(), method,
                  setting, static_cast<unsigned long long>(rays), seconds, estimated, e.measured,
                  e.reference_noise, e.mean_ratio);
    csv << line;
    std::printf("%s", line);
    std::fflush(stdout);
  };
  for (const auto& scene_path : a.scenes) {
    const std::string scene = fs::path(scene_path).stem().string();
    compiler::SceneConfig config = compiler::load_scene_config(scene_path);
    std::vector<compiler::SurfacePoint> points;
    std::unique_ptr<compiler::PathReference> reference;
    for (const std::string& way : a.direct) {
      if (way != "gather" && way != "shoot" && way != "gather-flat" && way != "gather-refined" &&
          way != "gather-final")
        throw walk::Error("walk bench lighting: --direct '" + way +
                          "' is not gather, gather-refined, gather-final, gather-flat or shoot");
      compiler::SceneConfig scene_config = config;  // each way starts from the scene's own settings
      scene_config.lighting.gather_direct = way != "shoot";
      if (way != "gather") {
        scene_config.lighting.refine = way == "gather-refined" || way == "gather-final";
        scene_config.lighting.gather_indirect = way == "gather-final";
      }
      const std::string method = "walk-" + way;
      for (const double target : a.targets) {
        scene_config.lighting.target_error = target;
        const auto compiled = compiler::compile_scene(scene_config, {a.threads});
        const std::string path = (tmp / (scene + ".walk")).string();
        model::write_bundle(path, compiled.bundle);
        const auto bundle = model::Bundle::open(path);
        if (!reference) {  // the surfaces are the same at every target: one reference serves them all
          points = compiler::surface_points(*bundle, a.points);
          const compiler::PathTracer tracer(*bundle);
          reference = std::make_unique<compiler::PathReference>(
              tracer.trace(points, a.reference_paths, 1, a.threads));
          std::fprintf(
              stderr, "%s: %zu of %zu points hidden (inside solids or behind lamps), left out\n",
              scene.c_str(),
              static_cast<std::size_t>(std::count(reference->hidden.begin(), reference->hidden.end(), 1)),
              points.size());
          for (const int paths : a.paths) {
            const auto r = tracer.trace(points, paths, 2 + paths, a.threads);
            std::vector<double> values;
            for (const auto& v : r.radiosity) values.push_back(model::luminance_weight(v));
            row(scene, "reference", paths, r.rays, r.seconds, 0.0, error_against(values, *reference));
          }
        }
        double seconds = 0.0, estimated = 0.0;
        std::uint64_t rays = 0;
        for (const auto& s : compiled.stages) {
          if (s.name != "light") continue;
          seconds = s.seconds;
          rays = s.items_out;
          estimated = s.estimated_error.value_or(0.0);
        }
        std::vector<double> values;
        const compiler::StoredLight stored(*bundle);  // read by position: each target dices its own way
        for (const auto& p : points)
          values.push_back(model::luminance_weight(stored.on_surface(p.position, p.normal)));
        row(scene, method.c_str(), target, rays, seconds, estimated, error_against(values, *reference));
        print_worst(scene + " " + method, points, values, *reference, a.worst);
      }
    }
  }
  fs::remove_all(tmp);
  if (!a.plot.empty()) {
    std::ostringstream commands;
    commands << "set logscale xy\nset key outside\nset xlabel 'seconds (light stage; reference tracing)'\n"
             << "set ylabel 'relative RMS error against the converged reference'\n"
             << "set title 'Light accuracy against time (walk bench lighting)'\nplot ";
    bool first = true;
    for (const auto& scene_path : a.scenes) {
      const std::string scene = fs::path(scene_path).stem().string();
      std::vector<std::string> methods{"reference"};
      for (const auto& way : a.direct) methods.push_back("walk-" + way);
      for (const auto& method : methods) {
        commands << (first ? "" : ", ") << "'" << plot_data_path(a.plot) << "' using ((strcol(1) eq '"
                 << scene << "' && strcol(2) eq '" << method << "') ? $5 : 1/0):7 with linespoints title '"
                 << scene << " " << method << "'";
        first = false;
      }
    }
    commands << "\n";
    plot_with_gnuplot(a.plot, csv.str(), commands.str());
  }
  return 0;
}

}  // namespace bench_lighting_command

void add_bench_lighting_command(CLI::App& bench, int& exit_code) {
  using namespace bench_lighting_command;
  auto args = std::make_shared<Args>();
  auto* cmd = bench.add_subcommand(
      "lighting",
      "Light error against a path-traced reference, by target_error and by reference paths (CSV)");
  cmd->add_option("--scenes", args->scenes, "Scene configs (default: the Cornell box and the house)")
      ->delimiter(',');
  cmd->add_option("--targets", args->targets, "target_error values to compile at")->delimiter(',');
  cmd->add_option("--direct", args->direct,
                  "Ways of direct light to compare: gather (refined as the scene says), gather-refined, "
                  "gather-flat, shoot")
      ->delimiter(',');
  cmd->add_option("--paths", args->paths, "Reference paths per point to time")->delimiter(',');
  cmd->add_option("--points", args->points, "Surface points compared")->check(CLI::Range(1, 1000000));
  cmd->add_option("--reference-paths", args->reference_paths, "Paths per point of the converged reference")
      ->check(CLI::Range(1, 100000000));
  cmd->add_option("--worst", args->worst, "Also print (stderr) this many points with the largest errors")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("-j,--threads", args->threads, "Worker threads");
  cmd->add_option("--plot", args->plot, "Also write this PNG (and its CSV beside it) with gnuplot");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace walk::tools
