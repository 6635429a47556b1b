// walk render x.walk --eye x,y,z --look x,y,z -o frame.png: one frame through a headless (or window) backend.
#include <spdlog/spdlog.h>

#include <array>
#include <iostream>
#include <sstream>
#include <vector>

#include "model/bundle.hpp"
#include "model/error.hpp"
#include "render/backend/backend.hpp"
#include "render/renderer.hpp"
#include "tools/commands.hpp"
#include "tools/option_vectors.hpp"

namespace walk::tools {
namespace render_command {  // named: walk compiles its commands as one unit

struct RenderArgs {
  std::string bundle;
  std::string output = "frame.png";
  std::vector<double> eye;
  std::vector<double> look;
  std::string size = "1280x720";
  std::string backend = "auto";
  std::vector<float> dimmers;
  double fov = 60.0;
  bool map = false;
  int refine = 0;  // 0: one plain frame; N: converge adaptive refinement with N anti-aliasing samples
};

int run_render(const RenderArgs& args) {
  const auto size = parse_frame_size(args.size, 16384);
  if (!size) throw Error("--size '" + args.size + "' is not WIDTHxHEIGHT (e.g. 1280x720)");
  const auto [width, height] = *size;
  auto bundle = model::Bundle::open(args.bundle);
  render::BackendOptions options;
  options.kind = render::parse_backend_kind(args.backend);
  options.width = width;
  options.height = height;
  auto backend = render::Backend::create(options);
  backend->make_current();
  render::Renderer renderer(*bundle);
  if (!args.dimmers.empty()) renderer.set_dimmers(args.dimmers);
  render::View view;
  view.eye = option_vec3(args.eye, "eye", "in local metres");
  view.forward = option_vec3(args.look, "look", "in local metres") - view.eye;
  view.fov_y_degrees = args.fov;
  renderer.set_map_overlay(args.map);
  if (args.refine > 0) {
    render::RefineSettings settings;
    settings.aa_samples = args.refine;
    renderer.set_refine_settings(settings);
    while (renderer.refine(view, width, height)) {
    }
  } else {
    renderer.draw(view, width, height);
  }
  render::write_png(args.output, renderer.read_pixels(width, height));
  const auto& stats = renderer.last_stats();
  std::cout << "wrote " << args.output << " (" << width << "x" << height << ", backend " << backend->name()
            << ", cell " << stats.cell << ", " << stats.polygons_drawn << " polygons)\n";
  return 0;
}

}  // namespace render_command

void add_render_command(CLI::App& app, int& exit_code) {
  using namespace render_command;
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render one frame of a bundle to PNG");
  cmd->add_option("bundle", args->bundle, "Compiled .walk bundle")->required();
  cmd->add_option("-o,--output", args->output, "PNG to write");
  cmd->add_option("--eye", args->eye, "Eye position x,y,z (local metres)")->delimiter(',')->required();
  cmd->add_option("--look", args->look, "Point looked at x,y,z (local metres)")->delimiter(',')->required();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT");
  cmd->add_option("--backend", args->backend, "auto, osmesa, egl, glfw or gbm");
  cmd->add_option("--dimmers", args->dimmers, "Dimmer level per circuit, 0..1")->delimiter(',');
  cmd->add_option("--fov", args->fov, "Vertical field of view, degrees");
  cmd->add_flag("--map", args->map,
                "Overlay the floor plan (top right) with the viewer's position and the compile's largest "
                "leak path (yellow)");
  cmd->add_option(
         "--refine", args->refine,
         "Refine as a still kiosk does (patches, diagonals, subdivision) with N anti-aliasing samples")
      ->check(CLI::Range(1, 1024));
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace walk::tools
