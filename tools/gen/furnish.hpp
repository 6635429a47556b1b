#pragma once
// Furnishing a storey: objects from the catalogue, each in a room drawn by floor area, on the floor at a
// random spot and quarter turn, clear of walls, doorways and each other.
#include <string>
#include <utility>
#include <vector>

#include "compiler/radiosity/sampling.hpp"
#include "tools/gen/building.hpp"
#include "tools/gen/building_writer.hpp"
#include "tools/gen/floor_loops.hpp"

namespace walk::gen {

// The compiler's SplitMix64 stream: the same numbers on every platform and standard library (std's
// distributions do not promise that), so the same seed writes the same bytes.
using SeededRandom = compiler::SplitMix;

struct RoomFloor {
  std::string name;
  std::vector<Loop2> loops;  // outer then holes, world metres
  double area = 0.0;
  double z = 0.0;
  std::vector<std::pair<glm::dvec2, glm::dvec2>> doorways;  // boxes of the doorways' thresholds
};

// Throws walk::Error naming --furnish when `density` objects per square metre would cover more of a floor
// than any room can take, before anything is placed.
void check_furnish_density(const FurnitureCatalogue& cat, double density);

// Places density x the rooms' floor area objects (rounded at random). Throws walk::Error naming --furnish
// when every room is full before they are all placed.
void furnish_storey(BuildingWriter& out, Building& b, const FurnitureCatalogue& cat,
                    const std::vector<RoomFloor>& rooms, double density, SeededRandom& rng);

}  // namespace walk::gen
