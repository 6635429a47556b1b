// walk: the display compiler and its companions (compile, inspect, render).
#include <spdlog/spdlog.h>

#include <iostream>

#include "common/progress.hpp"
#include "model/error.hpp"
#include "model/version.hpp"
#include "tools/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"walk: compile, inspect and render Walkthrough bundles"};
  app.require_subcommand(1);
  app.fallthrough();  // -v and --progress also after the subcommand: walk compile x.toml --progress log
  app.option_defaults()->always_capture_default();  // --help shows every option's default
  app.set_version_flag("--version", std::string("walk ") + walk::version());
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log each stage as it runs");
  std::string progress = "auto";
  app.add_option(
         "--progress", progress,
         "Progress of long work: bar (with rate and ETA), log (a line every 5 s), none; auto is bar on a "
         "terminal, log otherwise and under systemd")
      ->check(CLI::IsMember({"auto", "bar", "log", "none"}));
  int exit_code = 0;
  walk::tools::add_compile_command(app, exit_code);
  walk::tools::add_inspect_command(app, exit_code);
  walk::tools::add_render_command(app, exit_code);
  walk::tools::add_verify_command(app, exit_code);
  walk::tools::add_probe_command(app, exit_code);
  walk::tools::add_export_command(app, exit_code);
  walk::tools::add_gen_command(app, exit_code);
  auto* bench = app.add_subcommand("bench", "Accuracy and speed sweeps, printed as CSV");
  bench->require_subcommand(1);
  walk::tools::add_bench_radiosity_command(*bench, exit_code);
  walk::tools::add_bench_rays_command(*bench, exit_code);
  walk::tools::add_bench_render_command(*bench, exit_code);
  walk::tools::add_bench_cells_command(*bench, exit_code);
  walk::tools::add_bench_lighting_command(*bench, exit_code);
  walk::tools::add_bench_image_command(*bench, exit_code);
  app.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::warn);
    walk::ProgressStyle style = walk::ProgressStyle::Auto;
    walk::parse_progress_style(progress, style);  // checked by IsMember above
    walk::set_progress_style(style);
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const walk::Error& e) {
    std::cerr << "walk: error: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}
