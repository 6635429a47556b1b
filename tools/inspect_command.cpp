// walk inspect x.walk: what a bundle holds, after full validation.
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <vector>

#include "model/bundle.hpp"
#include "model/model.hpp"
#include "tools/commands.hpp"
#include "tools/pvs_stats.hpp"

namespace walk::tools {
namespace inspect_command {  // named: walk compiles its commands as one unit

int inspect(const std::string& path, bool list) {
  const auto b = model::Bundle::open(path);
  const auto& m = b->meta();
  std::printf("bundle %s: %llu bytes, format version %u, scene hash %016llx\n", path.c_str(),
              static_cast<unsigned long long>(b->file_size()), model::kBundleVersion,
              static_cast<unsigned long long>(m.scene_hash));
  std::printf("compiled by       %s\n",
              m.compiler_version ? std::string(b->string(m.compiler_version)).c_str() : "(not recorded)");
  std::printf("origin (world m)  %.3f %.3f %.3f\n", m.origin[0], m.origin[1], m.origin[2]);
  std::printf("bounds (local m)  %.3f %.3f %.3f .. %.3f %.3f %.3f\n", m.bounds_min[0], m.bounds_min[1],
              m.bounds_min[2], m.bounds_max[0], m.bounds_max[1], m.bounds_max[2]);
  std::size_t per_role[5] = {};
  for (const auto& p : b->polygons()) ++per_role[p.role];
  std::printf("polygons          %zu (opaque %zu, glass %zu, luminaire panels %zu)\n", b->polygons().size(),
              per_role[0], per_role[1], per_role[3]);
  std::printf("vertices          %zu\ntriangles         %zu\n", b->vertices().size(),
              b->indices().size() / 3);
  std::printf("materials         %zu\nrooms (groups)    %zu\n", b->materials().size(), b->groups().size());
  std::printf("luminaires        %zu\ncircuits          %zu\n", b->luminaires().size(), b->circuits().size());
  std::printf("cells             %zu (tree nodes %zu, PVS entries %zu)\n", b->cells().size(),
              b->nodes().size(), b->pvs().size());
  std::size_t one_way = 0;
  for (const auto& p : b->portals())
    one_way += (p.flags & (model::kPortalForward | model::kPortalBackward)) !=
               (model::kPortalForward | model::kPortalBackward);
  std::printf("portals           %zu (%zu one-way)\n", b->portals().size(), one_way);
  std::printf("clusters          %zu%s\n",
              b->clusters().empty() ? b->polygons().size() : b->clusters().size(),
              b->clusters().empty() ? " (one per polygon)" : "");
  if (!b->textures().empty()) {
    std::size_t mapped = 0;
    for (const auto& p : b->polygon_textures()) mapped += p.texture != model::kNoTextureRecord ? 1 : 0;
    std::printf("albedo maps       %zu (%.1f MiB) on %zu polygons:", b->textures().size(),
                double(b->texels().size()) / (1 << 20), mapped);
    for (const auto& t : b->textures())
      std::printf(" %s %ux%u", std::string(b->string(t.name)).c_str(), t.width, t.height);
    std::printf("\n");
  }
  if (!b->cells().empty()) {
    const PvsTriangles t = pvs_triangles(*b);
    std::printf(
        "PVS draws         %.0f triangles on average over %zu walk cells (worst %llu) of %llu: 1/%.1f\n",
        t.average, t.walk_cells, static_cast<unsigned long long>(t.worst),
        static_cast<unsigned long long>(t.total), t.average > 0.0 ? double(t.total) / t.average : 0.0);
  }
  std::printf("ambient %.4f W/m2 per albedo, exposure %.4f W/m2 = white\n", m.ambient, m.exposure);
  std::printf("stages:\n");
  for (const auto& s : b->stages())
    std::printf("  %-11s %-8s %8.3f s  in %llu out %llu\n", std::string(b->string(s.name)).c_str(),
                s.ran == 1 ? "ran" : (s.ran == 2 ? "reused" : "skipped"), s.seconds,
                static_cast<unsigned long long>(s.items_in), static_cast<unsigned long long>(s.items_out));
  if (list) {
    std::printf("circuits:\n");
    std::vector<double> peaks(b->circuits().size(), 0.0);  // green channel, per circuit
    const auto light = b->light();
    for (std::size_t v = 0; v < light.rows(); ++v)
      for (const model::LightEntry& e : light.row(v))
        peaks[e.circuit] = std::max<double>(peaks[e.circuit], e.rgb[1]);
    for (std::size_t c = 0; c < b->circuits().size(); ++c) {
      const double peak = peaks[c];
      const auto& r = b->circuits()[c];
      std::printf("  %2zu %-24s default %.2f  peak B %.2f W/m2  shown %s (compact error %.2f%%)\n", c,
                  std::string(b->string(r.name)).c_str(), r.default_level, peak,
                  r.light_form == model::LightForm::Compact ? "compact" : "full", 100.0 * r.compact_error);
    }
    std::printf("rooms:\n");
    for (std::size_t g = 0; g < b->groups().size(); ++g)
      std::printf("  %2zu %s\n", g, std::string(b->string(b->groups()[g].name)).c_str());
  }
  return 0;
}

}  // namespace inspect_command

void add_inspect_command(CLI::App& app, int& exit_code) {
  using namespace inspect_command;
  auto path = std::make_shared<std::string>();
  auto list = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("inspect", "Validate a bundle and print what it holds");
  cmd->add_option("bundle", *path, "Bundle to inspect")->required();
  cmd->add_flag("-l,--list", *list, "Also list circuits and rooms");
  cmd->callback([path, list, &exit_code] { exit_code = inspect(*path, *list); });
}

}  // namespace walk::tools
