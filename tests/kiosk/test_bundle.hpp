#pragma once
// A small in-memory building for navigation and daemon tests: two rooms side by side along x.
//   Room "A": x 0..4, y 0..4, floor z 0.      Room "B": x 4..8, y 0..4, floor z 0.29 (a 0.29 m step up).
//   Partition x = 4 with a door (Opening polygon) y 1.5..2.5, z 0.29..2.1: its sill is the 0.29 m riser.
//   A platform in room A: x 1..2, y 3..4, top z 0.5 (too high to step on). The wall at x = 0 is Glass.
//   Ceiling at z 3 faces down. Circuits "A" and "B"; one cell per room split by the plane x = 4.
#include <string>

#include "model/bundle.hpp"

namespace walk::kiosk::testing {

model::BundleContents two_room_contents();
// Writes two_room_contents() to `path` (world origin offset by (100, 200, 10)) and returns the path.
std::string write_two_room_bundle(const std::string& path);

}  // namespace walk::kiosk::testing
