#include "compiler/import/map_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <sstream>

#include "compiler/import/map_parser.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;

// Quake's defaults (id's light.exe): a light without a value is 300; a spotlight's cone is 20 degrees wide.
constexpr double kDefaultLight = 300.0;
constexpr double kDefaultSpotAngleDegrees = 20.0;

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

enum class Kind { World, Door, Trigger, Other };

Kind kind_of(const std::string& classname) {
  if (classname == "worldspawn") return Kind::World;
  if (classname == "func_door" || classname == "func_door_secret") return Kind::Door;
  if (starts_with(classname, "trigger_")) return Kind::Trigger;
  return Kind::Other;
}

bool parse_vec3(const std::string& text, Vec3& out) {
  std::istringstream in(text);
  in >> out.x >> out.y >> out.z;
  return !in.fail() && std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z);
}

double number_or(const MapEntity& e, const std::string& key, double fallback, const std::string& file);

// Light styles and spawnflags are small integers; anything else is refused before it is cast (a fuzzed
// "style" of 2e127 overflowed int).
constexpr double kLargestEntityInteger = 1e6;

int integer_or(const MapEntity& e, const std::string& key, int fallback, const std::string& file) {
  const double v = number_or(e, key, fallback, file);
  if (std::abs(v) > kLargestEntityInteger || v != std::floor(v))
    throw Error(located(
        file, e.line,
        "entity key \"" + key + "\" needs a whole number up to 1000000, found \"" + e.keys.at(key) + "\"",
        "fix the entity's value"));
  return static_cast<int>(v);
}

double number_or(const MapEntity& e, const std::string& key, double fallback, const std::string& file) {
  const auto it = e.keys.find(key);
  if (it == e.keys.end()) return fallback;
  std::istringstream in(it->second);
  double v = 0.0;
  in >> v;
  if (in.fail() || !std::isfinite(v))
    throw Error(located(file, e.line,
                        "entity key \"" + key + "\" needs a number, found \"" + it->second + "\"",
                        "fix the entity's value"));
  return v;
}

struct LightBuilder {
  const std::string& file;
  double scale;
  model::Model& model;
  MapStats& stats;
  std::map<std::string, Vec3> targets;  // targetname -> origin, for spotlights
  std::map<std::string, std::uint32_t> circuits;
  std::map<std::uint32_t, bool> circuit_on;

  void add(const MapEntity& e) {
    Vec3 origin;
    if (!parse_vec3(e.get("origin"), origin))
      throw Error(located(file, e.line, e.get("classname") + " has no valid \"origin\" (\"x y z\")",
                          "give the light entity an origin"));
    const double value = number_or(e, "light", number_or(e, "_light", kDefaultLight, file), file);
    Vec3 colour(1.0);
    const std::string colour_text = e.get("_color", e.get("color"));
    if (!colour_text.empty()) {
      if (!parse_vec3(colour_text, colour) || colour.x < 0 || colour.y < 0 || colour.z < 0)
        throw Error(
            located(file, e.line,
                    "light \"_color\" must be three non-negative numbers, found \"" + colour_text + "\"",
                    "fix the light's colour"));
      if (std::max({colour.x, colour.y, colour.z}) > 1.0) colour /= 255.0;  // 0..255 notation
    }
    model::Luminaire l;
    l.kind = model::LuminaireKind::Point;
    l.position = origin * scale;
    l.power = colour * (std::abs(value) * kWattsPerQuakeLight);
    const std::string target = e.get("target");
    if (!target.empty() && targets.count(target)) {
      const Vec3 axis = targets[target] - origin;
      if (glm::length(axis) > 0.0) {
        l.kind = model::LuminaireKind::Spot;
        l.normal = glm::normalize(axis);
        const double angle = number_or(e, "angle", kDefaultSpotAngleDegrees, file);
        l.cone = std::clamp(angle, 1.0, 360.0) * 0.5 * std::numbers::pi / 180.0;
        ++stats.spot_lights;
      }
    }
    const std::string targetname = e.get("targetname");
    const int style = integer_or(e, "style", 0, file);
    const std::string circuit = !targetname.empty() ? "switch " + targetname
                                : style != 0        ? "style " + std::to_string(style)
                                                    : std::string("static");
    auto [it, inserted] = circuits.emplace(circuit, static_cast<std::uint32_t>(model.circuits.size()));
    if (inserted) model.circuits.push_back({circuit, 1.0});
    // Switchable lights with START_OFF (spawnflags 1) start dark: the circuit's default level is 0 when every
    // light in it starts off.
    const bool on = !(integer_or(e, "spawnflags", 0, file) & 1) || targetname.empty();
    circuit_on[it->second] = circuit_on.count(it->second) ? (circuit_on[it->second] || on) : on;
    model.circuits[it->second].default_level = circuit_on[it->second] ? 1.0 : 0.0;
    l.circuit = it->second;
    l.name = e.get("classname") + "@" + std::to_string(e.line);
    model.luminaires.push_back(l);
    ++stats.lights;
  }
};

}  // namespace

model::Rgb texture_reflectance(const std::string& texture) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (char c : lower(texture)) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  model::Rgb rgb;
  for (int k = 0; k < 3; ++k) rgb[k] = 0.2 + 0.6 * static_cast<double>((h >> (16 * k)) & 0xffff) / 65535.0;
  return rgb;
}

model::Model read_map(const std::string& path, const MapOptions& options, MapStats* stats) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(located(path, 0, "cannot open the .map file", "check the path in the scene config"));
  std::ostringstream text;
  text << in.rdbuf();
  return read_map_text(text.str(), path, options, stats);
}

model::Model read_map_text(const std::string& text, const std::string& file, const MapOptions& options,
                           MapStats* stats_out) {
  if (!(options.unit_scale > 0.0) || !std::isfinite(options.unit_scale))
    throw Error(
        located(file, 0, "unit scale is not a positive number", "set `units` in the scene's [model]"));
  const MapFile map = parse_map(text, file);
  MapStats stats;
  stats.valve220 = map.valve220;
  model::Model model;
  model.csg_merged = true;
  model.materials.push_back({"default", {0.5, 0.5, 0.5}});
  std::map<std::string, std::uint32_t> materials;
  LightBuilder lights{file, options.unit_scale, model, stats, {}, {}, {}};
  for (const auto& e : map.entities) {
    Vec3 o;
    if (!e.get("targetname").empty() && parse_vec3(e.get("origin"), o))
      lights.targets[e.get("targetname")] = o;
  }
  std::size_t index = 0;
  std::vector<ConvexBrush> world;  // the worldspawn's brushes, once built (it is the first entity)
  std::vector<bool> world_solid;
  for (const auto& e : map.entities) {
    ++stats.entities;
    const std::string classname = e.get("classname");
    if (starts_with(classname, "light")) lights.add(e);
    stats.brushes += e.brushes.size();
    for (const auto& b : e.brushes) stats.brush_planes += b.planes.size();
    if (e.brushes.empty()) continue;
    const Kind kind = kind_of(classname);
    if (kind == Kind::Trigger) {
      stats.trigger_brushes += e.brushes.size();
      continue;
    }
    const std::string group_name =
        kind == Kind::World ? std::string("world") : classname + "#" + std::to_string(index++);
    const std::uint32_t group = model.group_index(group_name);
    std::vector<ConvexBrush> brushes;
    std::vector<const MapBrush*> sources;
    std::vector<bool> solid;
    for (const auto& b : e.brushes) {
      const bool all_clip = std::all_of(b.planes.begin(), b.planes.end(),
                                        [](const MapPlane& p) { return lower(p.texture) == "clip"; });
      if (all_clip) {
        ++stats.clip_brushes;
        continue;
      }
      std::vector<std::array<Vec3, 3>> points;
      for (const auto& p : b.planes) points.push_back(p.points);
      ConvexBrush brush;
      if (!build_brush(points, brush, stats.brush)) continue;
      const bool liquid = std::any_of(b.planes.begin(), b.planes.end(), [](const MapPlane& p) {
        return !p.texture.empty() && p.texture[0] == '*';
      });
      brushes.push_back(std::move(brush));
      sources.push_back(&b);
      solid.push_back(!liquid);
      ++stats.brushes_built;
      if (kind == Kind::Door) ++stats.door_brushes;
    }
    // Entities other than the world (doors, platforms, walls) are also clipped by the world's solid brushes
    // around them (listed after theirs, so the world's face wins where both lie on one plane): a door's faces
    // against its frame, floor and lintel disappear, and only its faces in the doorway stay.
    const std::size_t own = brushes.size();
    if (kind == Kind::World) {
      world = brushes;
      world_solid = solid;
      // The world's solid brushes are solids for the cells stage: nothing is seen or stands inside them.
      for (std::size_t b = 0; b < brushes.size(); ++b) {
        if (!solid[b]) continue;
        model::Solid volume;
        for (const auto& face : brushes[b].faces) {
          auto& out = volume.faces.emplace_back();
          for (const Vec3& v : face.winding) out.push_back(v * options.unit_scale);
        }
        model.solids.push_back(std::move(volume));
      }
    } else {
      model::Bounds box;
      for (const auto& b : brushes) {
        box.add(b.bounds.min);
        box.add(b.bounds.max);
      }
      for (std::size_t w = 0; w < world.size(); ++w) {
        if (!world_solid[w] || box.empty()) continue;
        bool apart = false;
        for (int k = 0; k < 3; ++k)
          apart = apart || world[w].bounds.max[k] < box.min[k] - kClipEpsilon ||
                  box.max[k] < world[w].bounds.min[k] - kClipEpsilon;
        if (apart) continue;
        brushes.push_back(world[w]);
        solid.push_back(true);
      }
    }
    for (auto& f : csg_faces(brushes, solid, stats.csg, own)) {
      const MapPlane& plane = sources[f.brush]->planes[brushes[f.brush].faces[f.face].plane];
      const std::string tex = lower(plane.texture);
      model::Polygon p;
      p.vertices.reserve(f.winding.size());
      for (const Vec3& v : f.winding) p.vertices.push_back(v * options.unit_scale);
      p.group = group;
      p.name = plane.texture;
      p.source_line = static_cast<std::uint32_t>(plane.line);
      if (kind == Kind::Door) p.role = model::Role::Opening;
      const bool sky = starts_with(tex, "sky");
      if (sky) {
        ++stats.sky_faces;
      } else if (!tex.empty() && tex[0] == '*') {
        p.role = model::Role::Glass;
        ++stats.liquid_faces;
      } else if (tex == "clip" || tex == "trigger") {
        continue;
      }
      auto [it, inserted] = materials.emplace(tex, static_cast<std::uint32_t>(model.materials.size()));
      // Sky faces stand for the open sky: drawn black, and light leaving through them never returns.
      if (inserted)
        model.materials.push_back(
            {plane.texture, sky ? model::Rgb{0.0} : texture_reflectance(plane.texture)});
      p.material = it->second;
      model.polygons.push_back(std::move(p));
    }
  }
  if (model.polygons.empty())
    throw Error(located(file, 0, "the .map file has no brush faces to draw", "is this a Quake .map level?"));
  if (stats_out) *stats_out = std::move(stats);
  return model;
}

}  // namespace walk::compiler
