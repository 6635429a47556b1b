// walk compile scene.toml -o x.walk: runs the display compiler and prints what each stage did.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <thread>

#include "compiler/pipeline.hpp"
#include "tools/commands.hpp"

namespace walk::tools {

void add_compile_command(CLI::App& app, int& exit_code) {
  struct Args {
    std::string scene, output = "scene.walk";
    bool force = false;
    unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 256u);  // 0 when unknown: 1
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("compile", "Compile a scene config into a .walk bundle");
  cmd->add_option("scene", args->scene, "Scene config (TOML)")->required();
  cmd->add_option("-o,--output", args->output, "Bundle to write");
  cmd->add_flag("-f,--force", args->force, "Recompile even when the bundle is up to date");
  cmd->add_option("-j,--threads", args->threads, "Worker threads (default: this machine's cores)")
      ->check(CLI::Range(1u, 256u));
  cmd->callback([args, &exit_code] {
    std::vector<compiler::StageReport> stages;
    compiler::CompileOptions options;
    options.threads = args->threads;
    if (!compiler::compile_to_file(args->scene, args->output, args->force, &stages, options)) {
      std::cout << args->output << " is up to date (scene hash unchanged); use --force to rebuild\n";
      exit_code = 0;
      return;
    }
    double total = 0.0;
    std::printf("%-11s %-4s %9s %10s %10s  %s\n", "stage", "ran", "seconds", "in", "out", "detail");
    for (const auto& s : stages) {
      std::printf("%-11s %-4s %9.3f %10llu %10llu  %s\n", s.name.c_str(),
                  s.ran ? "yes" : (s.reused ? "kept" : "no"), s.seconds,
                  static_cast<unsigned long long>(s.items_in), static_cast<unsigned long long>(s.items_out),
                  s.detail.c_str());
      total += s.seconds;
    }
    std::printf("wrote %s in %.3f s\n", args->output.c_str(), total);
    exit_code = 0;
  });
}

}  // namespace walk::tools
