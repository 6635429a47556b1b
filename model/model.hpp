#pragma once
// The in-memory building: what every importer produces and every compiler stage reads.
// Coordinates are double precision metres relative to `origin` (world = origin + local), so that models
// authored far from the world origin keep full precision; rendering converts local coordinates to float.
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/intensity_distribution.hpp"

namespace walk::model {

using Vec3 = glm::dvec3;
using Rgb = glm::dvec3;

// What a face is for. Opening faces (doors, open passages) are cut out of their host walls and are not drawn:
// they become holes the viewer walks through. Glass is drawn and blocks walking but not seeing.
enum class Role : std::uint8_t { Opaque = 0, Glass = 1, Opening = 2, Luminaire = 3, Ignored = 4 };

[[nodiscard]] const char* role_name(Role role);
[[nodiscard]] bool parse_role(const std::string& text, Role& out);

// An albedo map: 8-bit sRGB RGBA texels, rows from the bottom (v = 0) up, as GL samples them.
struct Texture {
  std::string name;  // as the model file names it
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4
  Rgb mean{1.0};                   // mean texel in linear light: what the solver multiplies into reflectance
};

inline constexpr std::uint32_t kNoTexture = UINT32_MAX;

struct Material {
  std::string name;
  // Diffuse reflectance per channel, 0..1; with an albedo map, the material's colour times the map's mean,
  // so the light solve sees the surface's average reflectance.
  Rgb reflectance{0.5, 0.5, 0.5};
  std::uint32_t texture = kNoTexture;  // index into Model::textures
};

// Texture coordinates over a planar polygon, an affine function of position: u(p) = dot(u_gradient, p) +
// u_offset, likewise v. Being a function of position, it survives every cut, split and re-dicing of the
// polygon, and a vertex made anywhere on it gets its coordinates without interpolation bookkeeping.
struct TextureMap {
  Vec3 u_gradient{0.0};
  double u_offset = 0.0;
  Vec3 v_gradient{0.0};
  double v_offset = 0.0;
  // Moves the map with its polygon when the polygon moves by `shift`.
  void translate(const Vec3& shift);
};

// A planar polygon, counter-clockwise seen from the side its normal points to. `group` names the room/zone
// it bounds (the DXF layer for EnergyPlus files); `source` is where it came from, for error messages.
struct Polygon {
  std::vector<Vec3> vertices;            // outer boundary, counter-clockwise about the normal
  std::vector<std::vector<Vec3>> holes;  // clockwise about the normal, inside the outer boundary
  std::uint32_t material = 0;
  Role role = Role::Opaque;
  std::uint32_t group = 0;  // index into Model::groups
  int color = 0;            // source colour number (DXF ACI), 0 when none
  std::string name;         // source name (EnergyPlus surface name), may be empty
  std::uint32_t source_line = 0;
  std::optional<TextureMap> texture_map;  // where its material has an albedo map and the file gave UVs
};

// What shape a luminaire emits from: an area panel, or a point (Quake `light` entities) emitting in all
// directions or, for a spot, into a cone about `normal`.
// Photometric: a point emitting as its measured intensity distribution (IES LM-63 or EULUMDAT), aimed
// along `normal` (gamma 0) with its C0 plane towards `u_axis`.
enum class LuminaireKind : std::uint8_t { Area = 0, Point = 1, Spot = 2, Photometric = 3 };

// An area luminaire: a rectangle centred at `position`, emitting into the half-space of `normal`. Point and
// spot luminaires use `position`, `power` and, for spots, `normal` (the cone axis), `cone` and `exponent`.
struct Luminaire {
  std::string name;
  LuminaireKind kind = LuminaireKind::Area;
  double cone = 3.141592653589793;  // spot: half-angle of the cone, radians (pi: a full sphere)
  double exponent = 0.0;  // spot: intensity falls off as cos(angle to axis)^exponent inside the cone
  Vec3 position{0.0};
  Vec3 normal{0.0, 0.0, -1.0};
  Vec3 u_axis{1.0, 0.0, 0.0};  // in-plane direction of `width`
  double width = 0.6;
  double height = 0.6;
  Rgb power{100.0, 100.0, 100.0};  // radiant power per channel, watts
  std::uint32_t circuit = 0;
  std::shared_ptr<const IntensityDistribution> distribution;  // Photometric only; its shape, not its scale
};

// An area luminaire's rectangle: its four corners, counter-clockwise about `normal`.
[[nodiscard]] std::array<Vec3, 4> panel_corners(const Luminaire& l);

// A light circuit: luminaires switched and dimmed together by one dimmer channel.
struct Circuit {
  std::string name;
  double default_level = 1.0;
};

// A convex volume that is solid all through (a Quake brush): no viewer stands in it and no sight line
// crosses it, so the cells stage closes portals where it cuts them and splits cells into the open parts
// it leaves. Its faces (outward, convex) need not all be drawn: faces inside other solids are not.
struct Solid {
  std::vector<std::vector<Vec3>> faces;
};

struct Model {
  Vec3 origin{0.0};  // world position of local (0,0,0), metres
  std::vector<Polygon> polygons;
  std::vector<Solid> solids;  // importers that know them (Quake's world brushes); empty otherwise
  // The importer merged its volumes by CSG (Quake's brushes): no face overlaps or is recessed behind another,
  // so there are no doors or windows to cut out of walls, and a liquid's surface just below a floor's
  // underside is not a window recessed into it.
  bool csg_merged = false;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<std::string> groups;
  std::vector<Luminaire> luminaires;
  std::vector<Circuit> circuits;

  // Returns the index of the group with this name, adding it when new.
  std::uint32_t group_index(const std::string& name);
};

struct Bounds {
  Vec3 min{1e300};
  Vec3 max{-1e300};
  void add(const Vec3& p);
  [[nodiscard]] bool empty() const { return min.x > max.x; }
  [[nodiscard]] Vec3 size() const { return max - min; }
  [[nodiscard]] Vec3 centre() const { return (min + max) * 0.5; }
};

[[nodiscard]] Bounds bounds_of(const Model& model);

// Newell's vector of a closed loop: normal to its best-fit plane, length twice its area (zero for fewer
// than three corners). Summed relative to the first corner, so a building far from the origin keeps its
// precision.
[[nodiscard]] Vec3 area_vector(const std::vector<Vec3>& loop);

}  // namespace walk::model
