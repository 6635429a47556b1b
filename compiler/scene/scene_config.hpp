#pragma once
// The scene config (TOML): which model to import, in which units, how its layers/colours/names map to roles
// and materials, which luminaires exist and which circuit each belongs to, and the lighting knobs.
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "compiler/partition/visibility_config.hpp"
#include "compiler/scene/plan_options.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// A rule maps faces to a role and/or a material; the first rule whose every given field matches wins.
struct FaceRule {
  std::optional<std::regex> layer;  // matched against the whole layer (group) name
  std::optional<std::regex> name;   // searched in the face name
  std::optional<int> color;         // DXF ACI colour
  std::optional<model::Role> role;
  std::optional<std::string> material;
  std::string where;  // "file:line" of the rule, for messages
};

// One ceiling panel per room, one circuit per room, for models that come without luminaires.
struct PanelsPerGroup {
  bool enabled = false;
  double width = 0.6, height = 0.6;
  double power = 60.0;  // radiant watts per panel
  model::Rgb colour{1.0, 1.0, 1.0};
  double drop = 0.02;  // below the ceiling, metres: keeps the panel off the ceiling plane
  std::optional<std::regex> exclude_groups;
};

struct CircuitRule {
  std::string name;
  std::regex luminaires;  // luminaire names searched
  double default_level = 1.0;
};

// Patch edges shorter than this (metres) would only multiply patches: 2 cm is finer than any display needs.
inline constexpr double kMinGrid = 0.02;

enum class LightingMethod { Radiosity, Direct };

struct LightingConfig {
  LightingMethod method = LightingMethod::Radiosity;
  double grid = 0.5;  // metres: patch edge length (the paper's 21 square-inch patches are about 0.12 m)
  int samples_per_luminaire = 8;  // direct light gathered: jittered points per area luminaire
  // radiosity: direct light gathered from the luminaires, only reflected light shot (Wallace, Elmquist &
  // Haines 1989); false (default): the luminaires shoot their light too (the paper's way). Gathered light
  // wins against the path-traced reference only with `refine` (docs/RADIOSITY.md)
  bool gather_direct = false;
  // with gathered direct light and a target: subdivide the dicing where direct light bends more than the
  // target allows (compiler/lighting/light_refinement.hpp). Off unless asked: it multiplies the triangles
  // the kiosk draws (the house: 6x) for still-image accuracy
  bool refine = false;
  // with gathered direct light: indirect light gathered at each display vertex from the solved patches
  // (compiler/lighting/final_gather.hpp) instead of interpolated from the patches around it, so it does
  // not follow the grid. Off unless asked: rays per vertex
  bool gather_indirect = false;
  double rays_per_watt = 1000.0;       // radiosity: rays shot per watt of unshot power (expert override)
  std::optional<double> target_error;  // radiosity: the solver's estimated error to reach; sets the rays
  double residual = 0.01;              // radiosity: stop when unshot power < residual * emitted
  std::string ray_caster = "axial";    // radiosity: "axial" (the paper's structure), "bvh", "embree-exact"
                                       // or "embree" if built (ray_caster.hpp)
  double ambient = 0.02;               // W/m2 per unit albedo added at display time for light not simulated
  std::optional<double> exposure;      // W/m2 shown as white; automatic when absent
};

// Where a walk through the scene begins: a point on a floor (world metres) and the direction faced.
struct StartPoint {
  model::Vec3 position{0.0};
  double heading = 0.0;  // radians, 0 = +x, counter-clockwise seen from above
};

struct SceneConfig {
  std::string path;        // the config file itself
  std::string model_file;  // absolute, resolved against the config's folder
  std::string format;      // "dxf", "plan" (2D DXF plan), "map" (Quake), or a mesh format read by assimp
  double metres_per_unit = 1.0;
  bool units_given = false;  // `units` or `scale` set; otherwise a DXF's $INSUNITS decides
  bool y_up = false;         // the file's y axis is up (`up = "y"`, the default for meshes); z is up inside
  double weld_metres = 0.0;  // [model] weld: corners closer than this merge; 0: relative to the model's size
  double seal_metres = 0.0;  // [model] seal: slits narrower than this between coplanar faces are filled
  bool keep_outliers = false;  // [model] outliers = "keep": faces far from the rest stay (see stray_geometry)
  std::vector<std::string> texture_dirs;  // [model] textures: folders searched for albedo maps (absolute)
  PlanOptions plan;                       // [plan]: how a 2D floor plan becomes 3D
  bool faces_point_outward = false;       // true: flip every face so it faces into its room (EnergyPlus)
  std::vector<FaceRule> rules;
  std::vector<model::Material> materials;
  PanelsPerGroup panels;
  std::vector<model::Luminaire> luminaires;     // explicit ones, world coordinates
  std::vector<std::string> luminaire_circuits;  // circuit name of each explicit luminaire
  std::vector<CircuitRule> circuits;
  LightingConfig lighting;
  VisibilityConfig visibility;      // [visibility]: cells, portals, PVS
  std::optional<StartPoint> start;  // [start]: where a walk begins, when the scene says
  std::string text;                 // the file's bytes, part of the scene hash
};

// Throws walk::Error naming the file, the line and the key for any problem.
[[nodiscard]] SceneConfig load_scene_config(const std::string& path);

}  // namespace walk::compiler
