#pragma once
// Writes a generated building as an ordinary scene: building.obj and building.mtl (the mesh, its groups
// and its materials' reflectances), scene.toml (roles by material, a ceiling panel and circuit per room,
// the start in the corridor) and kiosk.toml (walkd on the compiled bundle from that start). Every file is
// written under a temporary name and renamed, and only after all of them were written, so a failure
// leaves nothing behind and an old scene in the folder is replaced whole.
#include <string>

#include "tools/gen/building.hpp"

namespace walk::gen {

struct SceneFiles {
  std::string scene, mesh, materials, kiosk;  // the paths written
  std::uintmax_t bytes = 0;
};

// `command` is the command line that made the building, recorded in each file's header.
SceneFiles write_building_scene(const std::string& folder, const Building& building, const PlanUnit& plan,
                                const FurnitureCatalogue& furniture, const std::string& command);

// Names in OBJ and MTL files end at white space: spaces become underscores (and so do circuit names).
[[nodiscard]] std::string obj_name(const std::string& name);

}  // namespace walk::gen
