// walk export radiance x.walk DIR: the bundle as a Radiance scene (compiler/export/radiance_export.hpp), so a
// lighting designer can check our light with rtrace -I.
#include <cstdio>
#include <memory>
#include <string>

#include "compiler/export/radiance_export.hpp"
#include "model/bundle.hpp"
#include "tools/commands.hpp"

namespace walk::tools {

void add_export_command(CLI::App& app, int& exit_code) {
  auto* exporter = app.add_subcommand("export", "Write a compiled bundle in another tool's format");
  exporter->require_subcommand(1);
  struct Args {
    std::string bundle, folder;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = exporter->add_subcommand(
      "radiance", "Radiance scene (scene.rad: plastic and glass, light sources at the solver's power)");
  cmd->add_option("bundle", args->bundle, "Compiled bundle (.walk)")->required();
  cmd->add_option("folder", args->folder, "Folder to write scene.rad into (made if missing)")->required();
  cmd->callback([args, &exit_code] {
    const auto bundle = model::Bundle::open(args->bundle);
    const auto s = compiler::export_radiance(*bundle, args->folder);
    std::printf("wrote %s/scene.rad: %zu materials, %zu triangles, %zu panels, %zu point/spot sources",
                args->folder.c_str(), s.materials, s.polygons, s.panels, s.spheres);
    if (s.fixtures_approximated)
      std::printf(" (%zu measured fixtures as isotropic sources: convert their tables with ies2rad)",
                  s.fixtures_approximated);
    std::printf("\n");
    exit_code = 0;
  });
}

}  // namespace walk::tools
