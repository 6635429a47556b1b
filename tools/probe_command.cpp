// walk probe x.walk --at X,Y,Z [--normal NX,NY,NZ] [--look DX,DY,DZ] [--dimmers L0,L1,...]: illuminance in
// lux per circuit and for the dimmer mix, as a lighting designer checks a desk or a corridor.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "compiler/lighting/probe.hpp"
#include "model/bundle.hpp"
#include "model/error.hpp"
#include "tools/commands.hpp"
#include "tools/option_vectors.hpp"

namespace walk::tools {
namespace probe_command {  // named: walk compiles its commands as one unit

struct ProbeArgs {
  std::string bundle;
  std::vector<double> at, normal{0.0, 0.0, 1.0}, look;
  std::vector<double> dimmers;
  int rays = 16384;
};

int run_probe(const ProbeArgs& args) {
  const auto bundle = model::Bundle::open(args.bundle);
  const std::size_t circuits = bundle->circuits().size();
  std::vector<double> levels;
  for (const auto& c : bundle->circuits()) levels.push_back(c.default_level);
  if (!args.dimmers.empty()) {
    if (args.dimmers.size() != circuits) {
      std::string names;
      for (const auto& c : bundle->circuits())
        names += (names.empty() ? "" : ", ") + std::string(bundle->string(c.name));
      throw Error("walk probe: --dimmers gives " + std::to_string(args.dimmers.size()) +
                  " levels, the bundle has " + std::to_string(circuits) + " circuits (" + names + ")");
    }
    for (double l : args.dimmers)
      if (!(l >= 0.0 && l <= 1.0)) throw Error("walk probe: --dimmers levels must be between 0 and 1");
    levels = args.dimmers;
  }
  compiler::ProbeOptions o;
  o.at = option_vec3(args.at, "at", "in world metres");
  o.normal = option_vec3(args.normal, "normal");
  if (!args.look.empty()) o.look = option_vec3(args.look, "look");
  o.indirect_rays = args.rays;
  const auto r = compiler::Probe(*bundle).read(o);
  std::printf("probe at %.3f %.3f %.3f (world m), facing %.3f %.3f %.3f; %d indirect rays\n", o.at.x, o.at.y,
              o.at.z, o.normal.x, o.normal.y, o.normal.z, o.indirect_rays);
  std::printf("%-24s %6s %11s %11s %9s %11s %11s", "circuit", "level", "direct lx", "indirect lx", "+- lx",
              "total lx", "at level lx");
  if (o.look) std::printf(" %12s", "look cd/m2");
  std::printf("\n");
  double mix = 0.0, mix_error2 = 0.0, mix_look = 0.0;
  for (std::size_t c = 0; c < circuits; ++c) {
    const auto& x = r.circuits[c];
    const double total = x.direct_lux + x.indirect_lux;
    std::printf("%-24s %6.2f %11.2f %11.2f %9.2f %11.2f %11.2f", x.name.c_str(), levels[c], x.direct_lux,
                x.indirect_lux, x.indirect_standard_error, total, levels[c] * total);
    if (o.look) std::printf(" %12.3f", x.look_luminance);
    std::printf("\n");
    mix += levels[c] * total;
    mix_error2 += levels[c] * levels[c] * x.indirect_standard_error * x.indirect_standard_error;
    mix_look += levels[c] * x.look_luminance;
  }
  std::printf("mix: %.2f lx (+- %.2f lx indirect standard error)", mix, std::sqrt(mix_error2));
  if (o.look) {
    if (r.look_distance)
      std::printf("; the surface %.2f m along --look: %.3f cd/m2", *r.look_distance, mix_look);
    else
      std::printf("; --look meets no surface");
  }
  std::printf("\n");
  if (r.back_face_fraction > 0.05)
    std::printf(
        "warning: %.0f%% of the indirect rays met the back of a surface: the point may lie inside a wall "
        "or face away from its room\n",
        100.0 * r.back_face_fraction);
  if (bundle->luminaire_shapes().empty() && !bundle->luminaires().empty())
    std::printf(
        "warning: this bundle predates stored luminaire shapes, so every luminaire is read as an area "
        "panel; recompile it with this walk for point, spot and fixture light\n");
  return 0;
}

}  // namespace probe_command

void add_probe_command(CLI::App& app, int& exit_code) {
  using namespace probe_command;
  auto args = std::make_shared<ProbeArgs>();
  auto* cmd = app.add_subcommand("probe", "Illuminance (lux) at a point of a bundle, per circuit and mixed");
  cmd->add_option("bundle", args->bundle, "Compiled .walk bundle")->required();
  cmd->add_option("--at", args->at, "Meter position x,y,z: the scene's coordinates in metres, z up")
      ->delimiter(',')
      ->required();
  cmd->add_option("--normal", args->normal, "Direction the meter faces (default 0,0,1: a desk)")
      ->delimiter(',');
  cmd->add_option("--look", args->look, "Also the luminance of the surface met along this direction")
      ->delimiter(',');
  cmd->add_option("--dimmers", args->dimmers, "Dimmer level per circuit, 0..1 (default: each circuit's own)")
      ->delimiter(',');
  cmd->add_option("--rays", args->rays, "Indirect rays (more: a smaller standard error)")
      ->check(CLI::Range(1, 100000000));
  cmd->callback([args, &exit_code] { exit_code = run_probe(*args); });
}

}  // namespace walk::tools
