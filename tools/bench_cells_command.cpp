// `walk bench cells`: how the cells stage's cost grows with the model. For each size of the scale corpus it
// writes the building with `walk gen building`, compiles it in a child `walk compile` (so that each size's
// peak memory is its own, read with wait4), and prints the cells stage's seconds, cells and PVS with the
// compile's peak RSS as CSV; --plot draws seconds and memory against triangles with gnuplot.
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "model/bundle.hpp"
#include "tools/commands.hpp"
#include "tools/gnuplot.hpp"
#include "tools/pvs_stats.hpp"

extern char** environ;

namespace walk::tools {
namespace bench_cells_command {  // named: walk compiles its commands as one unit

struct Child {
  int status = -1;
  double peak_rss_mib = 0.0;
};

// Runs argv[0] with the rest as arguments, stdout and stderr to `log`; waits and reads its peak RSS.
Child run_child(const std::vector<std::string>& args, const std::string& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  Child out;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return out;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return out;
  out.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  out.peak_rss_mib = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
  return out;
}

// The generated scene gives each room its own circuit; the cells stage does not depend on circuits, so all
// go on one and the light stage the bench waits for stays as short as it can be.
void one_circuit(const std::string& scene_path) {
  std::ifstream in(scene_path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string changed = std::regex_replace(
      text.str(), std::regex("^circuit = \".*\"$", std::regex::multiline), "circuit = \"all\"");
  std::ofstream(scene_path) << changed;
}

struct Row {
  std::string size;
  std::uint64_t triangles = 0;
  double cells_seconds = 0.0;
  std::uint64_t polygons = 0, cells = 0;
  double pvs_average = 0.0;    // clusters listed per cell
  double drawn_average = 0.0;  // triangles a walk cell's PVS draws
  double peak_rss_mib = 0.0;
};

Row measure(const std::string& self, const std::string& size, const std::string& dir, unsigned threads) {
  std::filesystem::create_directories(dir);
  const Child gen = run_child({self, "gen", "building", "--size", size, "-o", dir}, dir + "/gen.log");
  if (gen.status != 0)
    throw std::runtime_error(fmt::format("walk gen building --size {} failed: see {}/gen.log", size, dir));
  one_circuit(dir + "/scene.toml");
  const Child compile = run_child({self, "compile", "-f", "-j", std::to_string(threads), dir + "/scene.toml",
                                   "-o", dir + "/building.walk"},
                                  dir + "/compile.log");
  if (compile.status != 0)
    throw std::runtime_error(
        fmt::format("compiling size {} failed (exit {}): see {}/compile.log", size, compile.status, dir));
  const auto bundle = model::Bundle::open(dir + "/building.walk");
  Row row;
  row.size = size;
  row.peak_rss_mib = compile.peak_rss_mib;
  for (const auto& s : bundle->stages())
    if (bundle->string(s.name) == "cells") {
      row.cells_seconds = s.seconds;
      row.polygons = s.items_in;
      row.cells = s.items_out;
    }
  std::size_t entries = 0, walked = 0;
  for (const auto& c : bundle->cells())
    if (!(c.flags & model::kCellOutside)) {
      entries += c.pvs_count;
      ++walked;
    }
  row.pvs_average = walked ? double(entries) / double(walked) : 0.0;
  row.triangles = bundle->indices().size() / 3;
  row.drawn_average = pvs_triangles(*bundle).average;
  return row;
}

int run_bench(const std::vector<std::string>& sizes, const std::string& work, unsigned threads,
              const std::string& plot) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::ostringstream csv;
  csv << "size,triangles,polygons,cells,pvs_clusters_avg,triangles_drawn_avg,cells_seconds,compile_peak_rss_"
         "mib\n";
  std::cout << csv.str() << std::flush;
  for (const auto& size : sizes) {
    const Row r = measure(self, size, work + "/" + size, threads);
    const std::string line =
        fmt::format("{},{},{},{},{:.1f},{:.0f},{:.2f},{:.0f}\n", r.size, r.triangles, r.polygons, r.cells,
                    r.pvs_average, r.drawn_average, r.cells_seconds, r.peak_rss_mib);
    csv << line;
    std::cout << line << std::flush;
  }
  if (!plot.empty()) {
    std::ostringstream commands;
    commands << "set logscale xy\nset key top left\nset xlabel 'triangles drawn by the bundle'\n"
             << "set ylabel 'cells stage seconds'\nset y2label 'whole compile peak RSS (MiB)'\nset y2tics\n"
             << "set logscale y2\nset title 'Cells stage cost against model size (walk bench cells)'\n"
             << "plot '" << plot_data_path(plot)
             << "' every ::1 using 2:7 with linespoints title 'cells stage s', "
             << "'' every ::1 using 2:7:1 with labels offset 1,1 notitle, "
             << "'' every ::1 using 2:8 axes x1y2 with linespoints title 'peak RSS MiB'\n";
    plot_with_gnuplot(plot, csv.str(), commands.str());
  }
  return 0;
}

}  // namespace bench_cells_command

void add_bench_cells_command(CLI::App& bench, int& exit_code) {
  using namespace bench_cells_command;
  struct Args {
    std::vector<std::string> sizes{"S", "M"};
    std::string work = "bench-cells";
    std::string plot;
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  };
  auto args = std::make_shared<Args>();
  auto* cmd = bench.add_subcommand(
      "cells", "Cells stage seconds and compile memory over the generated building sizes (CSV)");
  cmd->add_option("--sizes", args->sizes, "Sizes of `walk gen building` (S, M, L), in order")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--work", args->work, "Folder for the generated scenes and bundles")->capture_default_str();
  cmd->add_option("-j,--threads", args->threads, "Worker threads of each compile")->capture_default_str();
  cmd->add_option("--plot", args->plot, "Also write this PNG (and its CSV beside it) with gnuplot");
  cmd->callback(
      [args, &exit_code] { exit_code = run_bench(args->sizes, args->work, args->threads, args->plot); });
}

}  // namespace walk::tools
