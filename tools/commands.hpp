#pragma once
// Each `walk` subcommand registers itself on the app; the callback runs it and returns the exit code
// through `exit_code`.
#include <CLI/CLI.hpp>

namespace walk::tools {

void add_compile_command(CLI::App& app, int& exit_code);
void add_inspect_command(CLI::App& app, int& exit_code);
void add_render_command(CLI::App& app, int& exit_code);
void add_verify_command(CLI::App& app, int& exit_code);
// `walk probe`: illuminance at a point, per circuit (compiler/lighting/probe.hpp).
void add_probe_command(CLI::App& app, int& exit_code);
void add_export_command(CLI::App& app, int& exit_code);
// `walk gen building`: scale-corpus scenes of the shared models' parts.
void add_gen_command(CLI::App& app, int& exit_code);

// `walk bench ...`: accuracy/time sweeps printing CSV; each registers under the `bench` subcommand.
void add_bench_radiosity_command(CLI::App& bench, int& exit_code);
void add_bench_rays_command(CLI::App& bench, int& exit_code);
void add_bench_render_command(CLI::App& bench, int& exit_code);
void add_bench_cells_command(CLI::App& bench, int& exit_code);
void add_bench_lighting_command(CLI::App& bench, int& exit_code);
void add_bench_image_command(CLI::App& bench, int& exit_code);

}  // namespace walk::tools
