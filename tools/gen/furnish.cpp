#include "tools/gen/furnish.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <map>

#include "model/error.hpp"

namespace walk::gen {
namespace {

using glm::dvec2;
using model::Vec3;

// Furniture stands this far from walls and from each other, and keeps doorways this clear, metres.
constexpr double kWallClearance = 0.05, kObjectGap = 0.05, kDoorClearance = 0.6;
// A room is furnished up to this fraction of its floor in footprints; denser asks cannot fit.
constexpr double kMaxCoverage = 0.5;
// Random positions tried for each object before it is replaced by a smaller one.
constexpr int kPlacementTries = 400;

double uniform(SeededRandom& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.uniform();
}
// In [0, n): the modulo bias is below 2^-50 for the small n used here.
std::uint64_t below(SeededRandom& rng, std::uint64_t n) {
  return rng.next() % n;
}

struct Place {
  dvec2 lo, hi;  // the footprint's box, gaps included
};

// Tries to place object `o` in `room`: a random spot and quarter turn, kPlacementTries times. Writes it and
// returns true when it fits.
bool place_object(BuildingWriter& out, Building& b, const FurnitureCatalogue& cat, std::size_t o,
                  const RoomFloor& room, std::vector<Place>& placed, SeededRandom& rng) {
  dvec2 lo(1e300), hi(-1e300);
  for (const dvec2& p : room.loops.front()) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const FurnitureObject& obj = cat.objects[o];
  std::vector<std::pair<dvec2, dvec2>> keep_clear;
  for (const auto& [dlo, dhi] : room.doorways)
    keep_clear.emplace_back(dlo - kDoorClearance, dhi + kDoorClearance);
  for (int t = 0; t < kPlacementTries; ++t) {
    const int turns = static_cast<int>(below(rng, 4));
    const dvec2 half = (turns % 2 ? dvec2(obj.size.y, obj.size.x) : dvec2(obj.size.x, obj.size.y)) * 0.5;
    const dvec2 c(uniform(rng, lo.x, hi.x), uniform(rng, lo.y, hi.y));
    const dvec2 blo = c - half - kWallClearance, bhi = c + half + kWallClearance;
    if (!box_in_room(room.loops, blo, bhi)) continue;
    if (std::any_of(keep_clear.begin(), keep_clear.end(),
                    [&](const auto& d) { return boxes_overlap(blo, bhi, d.first, d.second); }))
      continue;
    const dvec2 glo = c - half - kObjectGap * 0.5, ghi = c + half + kObjectGap * 0.5;
    if (std::any_of(placed.begin(), placed.end(),
                    [&](const Place& q) { return boxes_overlap(glo, ghi, q.lo, q.hi); }))
      continue;
    placed.push_back({glo, ghi});
    PlacedObject po;
    po.room = room.name;
    po.object = o;
    po.triangles = obj.triangles;
    const std::string group = room.name + " " + obj.name + " #" + std::to_string(b.objects.size() + 1);
    std::map<std::uint32_t, std::size_t> parts;  // one part per material, its corners shared within it
    std::map<std::uint32_t, std::vector<std::uint32_t>> remap;
    for (const auto& f : obj.faces) {
      const auto [at, added] = parts.emplace(f.material, 0);
      if (added) at->second = out.part_index(group, "furniture " + cat.materials[f.material].name);
      MeshPart* part = &b.parts[at->second];
      auto& map = remap[f.material];
      if (map.empty()) map.assign(obj.vertices.size(), UINT32_MAX);
      std::vector<std::uint32_t> corners;
      for (std::uint32_t v : f.corners) {
        if (map[v] == UINT32_MAX) {
          Vec3 q = obj.vertices[v];
          for (int r = 0; r < turns; ++r) q = Vec3(-q.y, q.x, q.z);  // quarter turns are exact
          q += Vec3(c, room.z);
          map[v] = static_cast<std::uint32_t>(part->vertices.size());
          part->vertices.push_back(q);
          po.box.add(q);
        }
        corners.push_back(map[v]);
      }
      part->faces.push_back(std::move(corners));
    }
    b.triangles += obj.triangles;
    b.objects.push_back(po);
    return true;
  }
  return false;
}

}  // namespace

// A storey's share of furniture, density x its rooms' floor, each object in a room drawn by floor area.
// A room that cannot take an object is full, and the object goes to another; the density cannot fit when
// every room is full.
void furnish_storey(BuildingWriter& out, Building& b, const FurnitureCatalogue& cat,
                    const std::vector<RoomFloor>& rooms, double density, SeededRandom& rng) {
  double area = 0.0;
  for (const auto& r : rooms) area += r.area;
  const int wanted = static_cast<int>(std::floor(density * area + rng.uniform()));
  std::vector<std::vector<Place>> placed(rooms.size());
  std::vector<bool> full(rooms.size(), false);
  double open_area = area;
  std::size_t open_rooms = rooms.size();
  for (int n = 0; n < wanted; ++n) {
    const std::size_t o = below(rng, cat.objects.size());
    bool done = false;
    while (!done) {
      if (open_rooms == 0)
        throw Error(
            fmt::format("--furnish {}: the rooms of a storey ({:.1f} m2) take only {} of its {} objects; "
                        "ask for at most about {:.2f} objects per square metre",
                        density, area, n, wanted, 0.9 * n / area));
      double pick = rng.uniform() * std::max(open_area, 0.0);
      std::size_t r = 0;
      while (r + 1 < rooms.size() && (full[r] || pick >= rooms[r].area)) {
        if (!full[r]) pick -= rooms[r].area;
        ++r;
      }
      if (full[r]) {  // round-off at the end of the list: take the last open room
        while (full[r]) --r;
      }
      done = place_object(out, b, cat, o, rooms[r], placed[r], rng);
      if (!done) full[r] = true, open_area -= rooms[r].area, --open_rooms;
    }
  }
}

void check_furnish_density(const FurnitureCatalogue& cat, double density) {
  double mean_footprint = 0.0;
  for (const auto& o : cat.objects)
    mean_footprint += (o.size.x + kObjectGap) * (o.size.y + kObjectGap) / double(cat.objects.size());
  if (density * mean_footprint > kMaxCoverage)
    throw Error(
        fmt::format("--furnish {}: the objects would cover {:.0f}% of every floor; at most {:.2f} objects "
                    "per square metre fit",
                    density, 100 * density * mean_footprint, kMaxCoverage / mean_footprint));
}

}  // namespace walk::gen
