#include "tools/gen/building.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <map>
#include <numeric>
#include <polyclipping/clipper.hpp>

#include "compiler/geometry/clipper_convert.hpp"
#include "model/error.hpp"
#include "tools/gen/building_writer.hpp"
#include "tools/gen/floor_loops.hpp"
#include "tools/gen/furnish.hpp"

namespace walk::gen {
namespace {

using glm::dvec2;
using model::Vec3;

// The corridor between the two units and the lobbies at its ends, metres.
constexpr double kCorridorWidth = 1.8;
constexpr double kLobbyReach = 3.0;  // how far the lobbies reach past the corridor's sides
constexpr double kStairLobby = 4.4;  // south lobby, along the corridor: two stair lanes and a landing
constexpr double kLiftLobby = 3.8;   // north lobby: the lift shaft and room to walk past it
// The stair: risers near 19 cm (comfortable, and under the walker's 35 cm step), 25 cm treads, 1 m lanes.
constexpr double kTargetRiser = 0.19, kTread = 0.25, kStairWidth = 1.0;
// The lift shaft: outer side, wall thickness, and its door on each storey.
constexpr double kShaftSide = 2.4, kShaftWall = 0.2, kLiftDoorWidth = 1.0, kLiftDoorHeight = 2.1;
// Ceiling panels: below the ceiling by this much, the radiant watts of a room's panel, and the spacing and
// watts of the corridor's.
constexpr double kPanelDrop = 0.02, kRoomPanelWatts = 40.0;
constexpr double kCorridorPanelSpacing = 3.0, kCorridorPanelWatts = 20.0;

// Points closer than this to a boundary count as on it, metres (coordinates are built to 1 um).
constexpr double kOnBoundary = 1e-6;

std::string storey_label(int k) {
  char s[16];
  std::snprintf(s, sizeof s, "s%02d", k + 1);
  return s;
}

// The plan's polygons mirrored (x -> 2 mirror_x - x) or not, raised to storey k: what a unit contributes.
struct UnitCopy {
  std::string label;  // "A" or "B"
  bool mirrored = false;
  double mirror_x = 0.0;
  [[nodiscard]] dvec2 at(dvec2 p) const { return mirrored ? dvec2(2.0 * mirror_x - p.x, p.y) : p; }
};

std::string material_of(const model::Model& m, const model::Polygon& p) {
  if (p.role == model::Role::Opening) return "opening";
  if (p.role == model::Role::Glass) return "glass";
  return m.materials.at(p.material).name;
}

void emit_unit(BuildingWriter& out, const PlanUnit& plan, const UnitCopy& u, int k, double z0,
               std::vector<RoomFloor>& rooms) {
  const model::Model& m = plan.model;
  const std::string prefix = storey_label(k) + " " + u.label + " ";
  std::vector<std::pair<dvec2, dvec2>> doorways;
  // A horizontal polygon seen from above in this copy: its outer loop, then its holes.
  auto plan_loops = [&](const model::Polygon& p) {
    std::vector<Loop2> loops(1);
    for (const Vec3& q : p.vertices) loops[0].push_back(u.at(q));
    for (const auto& h : p.holes) {
      loops.emplace_back();
      for (const Vec3& q : h) loops.back().push_back(u.at(q));
    }
    return loops;
  };
  for (const auto& p : m.polygons) {
    const std::string group = prefix + m.groups[p.group];
    const std::string material = material_of(m, p);
    Vec3 n = model::area_vector(p.vertices);
    if (u.mirrored) n.x = -n.x;
    auto lift = [&](const std::vector<Vec3>& loop) {
      std::vector<Vec3> v;
      for (const Vec3& q : loop) v.emplace_back(u.at(q), q.z + z0);
      return v;
    };
    if (p.holes.empty()) {
      out.face(group, material, lift(p.vertices), n,
               std::abs(n.z) < 1e-9 * glm::length(n) && p.role != model::Role::Opening);
    } else {  // a floor or ceiling round a free-standing wall
      for (const Loop2& piece : without_holes(plan_loops(p)))
        out.flat(group, material, piece, p.vertices[0].z + z0, n.z > 0);
    }
    if (p.name == "threshold") {
      dvec2 lo(1e300), hi(-1e300);
      for (const Vec3& q : p.vertices) lo = glm::min(lo, u.at(q)), hi = glm::max(hi, u.at(q));
      doorways.emplace_back(lo, hi);
    }
    if (p.name == "floor" && m.groups[p.group].rfind("room ", 0) == 0 && n.z > 0) {
      RoomFloor r;
      r.name = group;
      r.z = z0;
      r.loops = plan_loops(p);
      r.area = std::abs(loop_area(r.loops[0]));
      for (std::size_t h = 1; h < r.loops.size(); ++h) r.area -= std::abs(loop_area(r.loops[h]));
      rooms.push_back(std::move(r));
    }
  }
  for (auto& r : rooms)
    if (r.name.rfind(prefix, 0) == 0) r.doorways = doorways;
}

}  // namespace

Building compose_building(const PlanUnit& plan, const FurnitureCatalogue& furniture,
                          const BuildingOptions& options) {
  if (options.storeys < 1)
    throw Error("--storeys: must be at least 1 (got " + std::to_string(options.storeys) + ")");
  if (!(options.furnish >= 0.0))
    throw Error("--furnish: must be 0 or more objects per square metre (got " +
                std::to_string(options.furnish) + ")");
  check_furnish_density(furniture, options.furnish);

  Building b;
  b.storeys = options.storeys;
  BuildingWriter out(b);
  const double H = plan.storey_height;
  const int risers = std::max(2, static_cast<int>(std::lround(H / kTargetRiser)));
  const double riser = H / risers, run = (risers - 1) * kTread;

  // Layout: unit A as drawn, unit B mirrored beyond the corridor along A's far side (+x), lobbies at the
  // corridor's ends (stair to the south, lift to the north).
  dvec2 lo(1e300), hi(-1e300);
  for (const dvec2& p : plan.outline) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double mirror_x = hi.x + kCorridorWidth / 2;
  const UnitCopy units[2] = {{"A", false, mirror_x}, {"B", true, mirror_x}};
  const dvec2 region_lo(hi.x - kLobbyReach, lo.y - kStairLobby);
  const dvec2 region_hi(hi.x + kCorridorWidth + kLobbyReach, hi.y + kLiftLobby);
  const double xc = mirror_x;
  const dvec2 shaft_lo(xc - kShaftSide / 2, region_hi.y - kShaftSide),
      shaft_hi(xc + kShaftSide / 2, region_hi.y);
  const dvec2 core_lo = shaft_lo + kShaftWall, core_hi = shaft_hi - kShaftWall;
  const double stair_x0 = xc - run / 2, stair_x1 = xc + run / 2;
  if (run > region_hi.x - region_lo.x - 2.0 || region_lo.y + 2 * kStairWidth > lo.y - 1.0)
    throw Error("--plan " + plan.name + ": the stair lobby is too small for a storey of " +
                std::to_string(H) + " m");

  // The corridor and lobbies: the box between and around the units, less the units and the shaft.
  ClipperLib::Clipper clip;
  clip.AddPath(to_path(rect(region_lo, region_hi)), ClipperLib::ptSubject, true);
  Loop2 outline_b;
  for (auto it = plan.outline.rbegin(); it != plan.outline.rend(); ++it)
    outline_b.push_back(units[1].at(*it));
  clip.AddPath(to_path(plan.outline), ClipperLib::ptClip, true);
  clip.AddPath(to_path(outline_b), ClipperLib::ptClip, true);
  clip.AddPath(to_path(rect(shaft_lo, shaft_hi)), ClipperLib::ptClip, true);
  ClipperLib::Paths region_paths;
  clip.Execute(ClipperLib::ctDifference, region_paths, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  ClipperLib::CleanPolygons(region_paths, 1.0);
  if (region_paths.size() != 1 || !ClipperLib::Orientation(region_paths[0]))
    throw Error("--plan " + plan.name + ": the corridor between the units is not one region (" +
                std::to_string(region_paths.size()) + " pieces)");
  const Loop2 corridor = to_loop(region_paths[0]);
  auto on_region_box = [&](dvec2 a, dvec2 b) {
    auto same = [](double u, double v, double w) {
      return std::abs(u - w) < kOnBoundary && std::abs(v - w) < kOnBoundary;
    };
    return same(a.x, b.x, region_lo.x) || same(a.x, b.x, region_hi.x) || same(a.y, b.y, region_lo.y) ||
           same(a.y, b.y, region_hi.y);
  };
  auto on_shaft = [&](dvec2 a, dvec2 b) {
    const dvec2 m = (a + b) * 0.5;
    return m.x > shaft_lo.x - kOnBoundary && m.x < shaft_hi.x + kOnBoundary &&
           m.y > shaft_lo.y - kOnBoundary && m.y < shaft_hi.y + kOnBoundary;
  };

  SeededRandom rng(options.seed);
  const int N = options.storeys;
  for (int k = 0; k < N; ++k) {
    const double z0 = k * H, z1 = z0 + H;
    const std::string s = storey_label(k);
    std::vector<RoomFloor> rooms;
    for (const UnitCopy& u : units) emit_unit(out, plan, u, k, z0, rooms);

    // Corridor floor, ceiling and the lobbies' outer walls (the units' outer walls line the rest).
    const std::string hall = s + " corridor";
    out.flat(hall, "floor", corridor, z0, true);
    out.flat(hall, "ceiling", corridor, z1, false);
    for (std::size_t i = 0; i < corridor.size(); ++i) {
      const dvec2 a = corridor[i], c = corridor[(i + 1) % corridor.size()];
      if (!on_region_box(a, c) || on_shaft(a, c)) continue;
      const dvec2 d = c - a;
      out.wall(hall, "wall", a, c, z0, z1, dvec2(-d.y, d.x));  // counter-clockwise: inside is on the left
    }

    // The open stair from this storey to the next: a solid flight in lane k % 2, rising +x on even storeys
    // and -x on odd ones, so the flights switch back; the floor above is open over the flight.
    const double lane_lo = region_lo.y + (k % 2) * kStairWidth, lane_hi = lane_lo + kStairWidth;
    if (k + 1 < N) {
      const std::string g = s + " stair";
      const double dir = k % 2 ? -1.0 : 1.0, x_start = k % 2 ? stair_x1 : stair_x0;
      auto X = [&](double u) { return x_start + dir * u; };
      std::vector<dvec2> profile{{0.0, 0.0}};  // (along the flight, height)
      for (int i = 0; i + 1 < risers; ++i) {
        profile.emplace_back(i * kTread, (i + 1) * riser);
        profile.emplace_back((i + 1) * kTread, (i + 1) * riser);
        out.face(g, "stair",
                 {{X(i * kTread), lane_lo, z0 + i * riser},
                  {X(i * kTread), lane_hi, z0 + i * riser},
                  {X(i * kTread), lane_hi, z0 + (i + 1) * riser},
                  {X(i * kTread), lane_lo, z0 + (i + 1) * riser}},
                 {-dir, 0, 0});
        out.face(g, "stair",
                 {{X(i * kTread), lane_lo, z0 + (i + 1) * riser},
                  {X((i + 1) * kTread), lane_lo, z0 + (i + 1) * riser},
                  {X((i + 1) * kTread), lane_hi, z0 + (i + 1) * riser},
                  {X(i * kTread), lane_hi, z0 + (i + 1) * riser}},
                 {0, 0, 1});
      }
      profile.emplace_back(run, 0.0);
      for (const double y : {lane_lo, lane_hi}) {
        std::vector<Vec3> side;
        for (const dvec2& q : profile) side.emplace_back(X(q.x), y, z0 + q.y);
        out.face(g, "stair", side, {0, y == lane_lo ? -1.0 : 1.0, 0});
      }
      const double top = z0 + (risers - 1) * riser;
      out.face(g, "stair",
               {{X(run), lane_lo, z0}, {X(run), lane_hi, z0}, {X(run), lane_hi, top}, {X(run), lane_lo, top}},
               {dir, 0, 0});
      // The last step is the edge of the floor above: faced both ways, since both sides are seen.
      for (const double facing : {-dir, dir})
        out.face(
            g, "stair",
            {{X(run), lane_lo, top}, {X(run), lane_hi, top}, {X(run), lane_hi, z1}, {X(run), lane_lo, z1}},
            {facing, 0, 0});
      // The hole over the flight, cut out of this storey's ceiling and the next storey's floor.
      const Loop2 hole = rect({stair_x0, lane_lo}, {stair_x1, lane_hi});
      out.flat(g, "opening", hole, z1, false);
      out.flat(storey_label(k + 1) + " stair", "opening", hole, z1, true);
    }

    // The lift shaft: walls of kShaftWall round an empty core, a door to the lobby on every storey.
    const std::string lift = "lift shaft";
    out.wall(lift, "wall", {shaft_lo.x, shaft_hi.y}, shaft_lo, z0, z1, {-1, 0});
    out.wall(lift, "wall", {shaft_hi.x, shaft_lo.y}, shaft_hi, z0, z1, {1, 0});
    out.wall(lift, "wall", shaft_lo, {shaft_hi.x, shaft_lo.y}, z0, z1, {0, -1});
    out.wall(lift, "wall", shaft_hi, {shaft_lo.x, shaft_hi.y}, z0, z1, {0, 1});
    out.wall(lift, "wall", core_lo, {core_lo.x, core_hi.y}, z0, z1, {1, 0});
    out.wall(lift, "wall", {core_hi.x, core_lo.y}, core_hi, z0, z1, {-1, 0});
    out.wall(lift, "wall", core_lo, {core_hi.x, core_lo.y}, z0, z1, {0, 1});
    out.wall(lift, "wall", {core_lo.x, core_hi.y}, core_hi, z0, z1, {0, -1});
    const double d0 = xc - kLiftDoorWidth / 2, d1 = xc + kLiftDoorWidth / 2, dz = z0 + kLiftDoorHeight;
    const std::string door = s + " lift door";
    out.wall(door, "opening", {d0, shaft_lo.y}, {d1, shaft_lo.y}, z0, dz, {0, -1});
    out.wall(door, "opening", {d0, core_lo.y}, {d1, core_lo.y}, z0, dz, {0, 1});
    out.wall(door, "wall", {d0, shaft_lo.y}, {d0, core_lo.y}, z0, dz, {1, 0});
    out.wall(door, "wall", {d1, shaft_lo.y}, {d1, core_lo.y}, z0, dz, {-1, 0});
    out.flat(door, "ceiling", rect({d0, shaft_lo.y}, {d1, core_lo.y}), dz, false);
    out.flat(door, "floor", rect({d0, shaft_lo.y}, {d1, core_lo.y}), z0, true);

    // Light: a panel at the middle of every room, panels along the corridor, one circuit each.
    for (const RoomFloor& r : rooms) {
      RoomInfo info;
      info.name = r.name;
      info.storey = k;
      info.area = r.area;
      info.panels.push_back({room_centre(r.loops), z1 - kPanelDrop});
      info.watts = kRoomPanelWatts;
      b.rooms.push_back(std::move(info));
    }
    RoomInfo hall_info;
    hall_info.name = hall;
    hall_info.storey = k;
    hall_info.area = std::abs(loop_area(corridor));
    hall_info.watts = kCorridorPanelWatts;
    for (double y = region_lo.y + kCorridorPanelSpacing / 2; y < region_hi.y; y += kCorridorPanelSpacing)
      if (inside({corridor}, {xc, y}) && !(y > shaft_lo.y - 0.5 && y < shaft_hi.y))
        hall_info.panels.push_back({xc, y, z1 - kPanelDrop});
    b.rooms.push_back(std::move(hall_info));

    if (options.furnish > 0.0) furnish_storey(out, b, furniture, rooms, options.furnish, rng);
  }
  // The shaft's pit and top.
  out.flat("lift shaft", "floor", rect(core_lo, core_hi), 0.0, true);
  out.flat("lift shaft", "ceiling", rect(core_lo, core_hi), N * H, false);
  // The envelope's ground slab and roof over the whole footprint, under and over the walls' hollow cores
  // too: a closed building, so the compile's inside flood finds no way out.
  {
    ClipperLib::Clipper all;
    all.AddPath(to_path(rect(region_lo, region_hi)), ClipperLib::ptSubject, true);
    all.AddPath(to_path(plan.outline), ClipperLib::ptClip, true);
    all.AddPath(to_path(outline_b), ClipperLib::ptClip, true);
    ClipperLib::Paths footprint;
    all.Execute(ClipperLib::ctUnion, footprint, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    ClipperLib::CleanPolygons(footprint, 1.0);
    for (const auto& path : footprint) {
      if (!ClipperLib::Orientation(path)) continue;  // a courtyard's hole: none in these plans
      out.flat("envelope", "floor", to_loop(path), 0.0, false);
      out.flat("envelope", "ceiling", to_loop(path), N * H, true);
    }
  }

  b.start = {xc, 0.5 * (lo.y + hi.y), 0.0};
  b.start_heading_deg = 90.0;
  return b;
}

}  // namespace walk::gen
