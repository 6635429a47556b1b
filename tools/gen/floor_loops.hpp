#pragma once
// Loops in the plane seen from above (floors, rooms, footprints), metres: the tests furniture placement and
// panel placement need, and the split of a floor with holes into faces an OBJ can hold.
#include <glm/vec2.hpp>
#include <polyclipping/clipper.hpp>
#include <vector>

namespace walk::gen {

using Loop2 = std::vector<glm::dvec2>;

// Signed area, positive when counter-clockwise.
[[nodiscard]] double loop_area(const Loop2& loop);
[[nodiscard]] ClipperLib::Path to_path(const Loop2& loop);
[[nodiscard]] Loop2 to_loop(const ClipperLib::Path& path);
// The box lo..hi, counter-clockwise.
[[nodiscard]] Loop2 rect(glm::dvec2 lo, glm::dvec2 hi);
// Even-odd over every loop: inside the outer boundary and outside its holes.
[[nodiscard]] bool inside(const std::vector<Loop2>& loops, glm::dvec2 p);
// Does segment a-b pass through the open box (lo, hi)?
[[nodiscard]] bool segment_enters_box(glm::dvec2 a, glm::dvec2 b, glm::dvec2 lo, glm::dvec2 hi);
// A box lies in a room (outer loop then holes) when its corners are inside and no edge enters it.
[[nodiscard]] bool box_in_room(const std::vector<Loop2>& room, glm::dvec2 lo, glm::dvec2 hi);
[[nodiscard]] bool boxes_overlap(glm::dvec2 alo, glm::dvec2 ahi, glm::dvec2 blo, glm::dvec2 bhi);
// The point of a room farthest from its walls, on a 5 cm grid.
[[nodiscard]] glm::dvec2 room_centre(const std::vector<Loop2>& room);
// A polygon with holes (outer loop first) as polygons without: OBJ faces have none.
[[nodiscard]] std::vector<Loop2> without_holes(const std::vector<Loop2>& loops);

}  // namespace walk::gen
