// `walk gen building`: writes a furnished multi-storey scene made of the shared models' real parts, the
// scale corpus every complex-building figure is measured on.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "model/error.hpp"
#include "tools/commands.hpp"
#include "tools/gen/building.hpp"
#include "tools/gen/furniture.hpp"
#include "tools/gen/plan_unit.hpp"
#include "tools/gen/scene_writer.hpp"

namespace walk::tools {
namespace gen_command {  // named: walk compiles its commands as one unit

// The conference room's file units: its copyright.txt says "Scale by 0.003 to get meters".
constexpr double kConferenceScale = 0.003;

struct GenOptions {
  std::string output;
  std::string plan = "apartment";
  std::optional<int> storeys;
  std::optional<double> furnish;
  std::uint64_t seed = 1;
  std::string size;
  std::string data, scenes;
};

std::string command_line(const GenOptions& o, int storeys, double furnish) {
  return fmt::format("walk gen building --plan {} --storeys {} --furnish {} --seed {}", o.plan, storeys,
                     furnish, o.seed);
}

int run_gen(const GenOptions& o) {
  gen::BuildingOptions b;
  if (!o.size.empty()) {
    const gen::SizePreset* preset = nullptr;
    for (const auto& p : gen::kSizePresets)
      if (o.size == p.name) preset = &p;
    if (!preset) throw Error("--size: unknown preset '" + o.size + "' (known: S, M, L)");
    b.storeys = preset->storeys;
    b.furnish = preset->furnish;
  }
  if (o.storeys) b.storeys = *o.storeys;
  if (o.furnish) b.furnish = *o.furnish;
  b.seed = o.seed;

  const gen::PlanUnit plan = gen::load_plan_unit(o.plan, o.scenes, o.data);
  const std::string room_file = (std::filesystem::path(o.data) / "conference-room/conference.obj").string();
  if (!std::filesystem::is_regular_file(room_file))
    throw Error(located(room_file, 0, "the conference room model is missing",
                        "give the shared data folder with --data"));
  const gen::FurnitureCatalogue furniture = gen::cut_furniture(room_file, kConferenceScale);
  spdlog::info("furniture: {} objects found, {} stand on the floor, {} distinct shapes", furniture.pieces,
               furniture.standing, furniture.objects.size());
  for (const auto& obj : furniture.objects)
    spdlog::info("furniture: {} {:.2f} x {:.2f} x {:.2f} m, {} triangles", obj.name, obj.size.x, obj.size.y,
                 obj.size.z, obj.triangles);
  const gen::Building building = gen::compose_building(plan, furniture, b);
  const std::string command = command_line(o, b.storeys, b.furnish);
  const auto files = gen::write_building_scene(o.output, building, plan, furniture, command);

  std::size_t rooms = 0;
  for (const auto& r : building.rooms) rooms += r.name.find("corridor") == std::string::npos;
  std::printf("wrote %s (%.1f MB): %s\n", files.scene.c_str(), files.bytes / 1e6, command.c_str());
  std::printf(
      "storeys %d rooms %zu corridors %zu objects %zu (%zu shapes) triangles %zu (structure %zu) "
      "circuits %zu\n",
      building.storeys, rooms, building.rooms.size() - rooms, building.objects.size(),
      furniture.objects.size(), building.triangles, building.structure_triangles, building.rooms.size());
  return 0;
}

}  // namespace gen_command

void add_gen_command(CLI::App& app, int& exit_code) {
  using namespace gen_command;
  auto* gen = app.add_subcommand("gen", "Generate scenes for measuring: the scale corpus");
  gen->require_subcommand(1);
  auto* building = gen->add_subcommand(
      "building",
      "A furnished multi-storey building of real parts: storeys of a shared plan round a corridor, an open "
      "stair and a lift shaft through the floors, furniture cut from the conference room, a ceiling panel "
      "and circuit per room");
  auto o = std::make_shared<GenOptions>();
  if (const char* env = std::getenv("WALK_SHARED_DATA"))
    o->data = env;
  else
    o->data = std::string(WALK_SOURCE_DIR) + "/../shared/data";
  o->scenes = std::string(WALK_SOURCE_DIR) + "/config/scenes";
  building
      ->add_option("-o,--output", o->output, "Folder to write scene.toml, building.obj/.mtl and kiosk.toml")
      ->required();
  building->add_option("--plan", o->plan, "Floor plan of each storey")->capture_default_str();
  building->add_option("--storeys", o->storeys, "Storeys (default 2, or the preset's)");
  building->add_option("--furnish", o->furnish,
                       "Objects per square metre of room floor (default 0.25, or the preset's)");
  building->add_option("--seed", o->seed, "Random seed: the same seed writes the same bytes")
      ->capture_default_str();
  building->add_option("--size", o->size, "Preset: S (~0.1 M triangles), M (~1 M) or L (~5 M)");
  building->add_option("--data", o->data, "Shared data folder (or WALK_SHARED_DATA)")->capture_default_str();
  building->add_option("--scenes", o->scenes, "Scene configs of the plans (the repository's config/scenes)")
      ->capture_default_str();
  building->callback([o, &exit_code] { exit_code = run_gen(*o); });
}

}  // namespace walk::tools
