#pragma once
// A furnished multi-storey building composed only of real parts: storeys of a shared floor plan (two
// units facing each other across a corridor, the second mirrored), a lobby at each end of the corridor
// with an open switchback stair through holes in the floors at one end and a lift shaft through every storey
// at the other, each room furnished with objects cut from the conference room and lit by a ceiling panel on
// a circuit of its own.
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "tools/gen/furniture.hpp"
#include "tools/gen/plan_unit.hpp"

namespace walk::gen {

struct BuildingOptions {
  int storeys = 2;
  double furnish = 0.25;  // objects per square metre of room floor
  std::uint64_t seed = 1;
};

// A preset: about 0.1 M (S), 1 M (M) and 5 M (L) triangles with the apartment plan.
struct SizePreset {
  const char* name;
  int storeys;
  double furnish;
};
inline constexpr SizePreset kSizePresets[] = {{"S", 2, 0.1}, {"M", 10, 0.18}, {"L", 50, 0.18}};

// One group and material of the written mesh: indexed faces, counter-clockwise about their normals.
struct MeshPart {
  std::string group;
  std::string material;
  std::vector<model::Vec3> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
};

struct WrittenMaterial {
  std::string name;
  model::Rgb reflectance{0.5};
};

struct RoomInfo {
  std::string name;  // the room's group and circuit: "s01 A room 3"
  int storey = 0;
  double area = 0.0;                // square metres of floor
  std::vector<model::Vec3> panels;  // ceiling panel centres, world metres
  double watts = 0.0;               // radiant watts of each panel
};

struct PlacedObject {
  std::string room;
  std::size_t object = 0;  // index into the catalogue
  model::Bounds box;       // world bounds of its faces
  std::size_t triangles = 0;
};

struct Building {
  std::vector<MeshPart> parts;
  std::vector<WrittenMaterial> materials;
  std::vector<RoomInfo> rooms;  // one circuit each: every room, and each storey's corridor
  std::vector<PlacedObject> objects;
  std::vector<model::Polygon> walls;  // every vertical structural face, world metres (for checks)
  model::Vec3 start{0.0};             // on the ground storey's corridor floor, world metres
  double start_heading_deg = 90.0;    // along the corridor
  int storeys = 0;
  std::size_t triangles = 0;  // of every face written, fans of their corners
  std::size_t structure_triangles = 0;
};

// Throws walk::Error naming the option when storeys < 1, furnish < 0, or the furniture cannot fit.
[[nodiscard]] Building compose_building(const PlanUnit& plan, const FurnitureCatalogue& furniture,
                                        const BuildingOptions& options);

}  // namespace walk::gen
