#pragma once
// Walking through a compiled building: the walker is a vertical cylinder (body circle, feet on a floor) that
// moves along its heading, collides with solid triangles (Opaque, Glass) in the band between step height and
// head height above its floor, slides along walls, steps up small rises and falls down larger drops.
// Opening polygons (doors, passages) are holes and never block. All positions are bundle-local metres.
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"

namespace walk::kiosk {

// Radius of the walker's body circle: shoulders of an adult, small enough to pass a 0.7 m door.
inline constexpr double kBodyRadius = 0.25;
inline constexpr std::uint32_t kNoPolygon = 0xffffffffu;

struct NavSettings {
  double body_radius = kBodyRadius;
  double step_height = 0.35;  // highest rise (door sill, stair step) the walker steps over
  double head_height = 1.8;   // top of the collision band above the floor
  double max_substep = 0.1;   // longest move tested at once, well under the radius so walls cannot be skipped
};

// The parts of a bundle navigation needs; spans into a Bundle or a BundleContents.
struct NavGeometry {
  std::span<const model::VertexRecord> vertices;
  std::span<const std::uint32_t> indices;
  std::span<const model::PolygonRecord> polygons;
};

struct FloorHit {
  double z = 0.0;
  std::uint32_t polygon = kNoPolygon;
};

class Navigator {
 public:
  Navigator(const NavGeometry& geometry, const NavSettings& settings = {});

  // Puts the walker's feet on the highest floor at or below `feet` + step height and makes that the start.
  // Returns false (walker unchanged) when there is no floor there or the body would overlap a wall.
  bool place(const glm::dvec3& feet);
  void return_to_start();

  // Walks `speed` m/s along `heading` (radians, 0 = +x, counter-clockwise) for `dt` seconds.
  void walk(double speed, double heading, double dt);
  // Moves by a horizontal displacement with collision, sliding and floor following.
  void move(const glm::dvec2& delta);

  [[nodiscard]] const glm::dvec3& feet() const { return feet_; }
  [[nodiscard]] std::uint32_t floor_polygon() const { return floor_polygon_; }
  [[nodiscard]] double distance_walked() const { return distance_; }
  [[nodiscard]] const NavSettings& settings() const { return settings_; }
  void set_settings(const NavSettings& settings) { settings_ = settings; }  // config reload; the grid stays

  // The highest upward-facing solid surface under (x, y) no higher than max_z.
  [[nodiscard]] std::optional<FloorHit> floor_at(const glm::dvec2& p, double max_z) const;
  // How deep the body circle at `p` overlaps solid geometry for a walker standing at `floor_z`; 0 when free.
  [[nodiscard]] double penetration(const glm::dvec2& p, double floor_z) const;

 private:
  struct Triangle {
    glm::dvec3 a, b, c;
    double z_min, z_max;
    glm::dvec2 lo, hi;  // 2D bounds
    std::uint32_t polygon;
  };
  struct Contact {
    double depth = 0.0;
    glm::dvec2 normal{0.0};  // pushes the circle out
  };

  void build_grid();
  template <typename F>
  void for_cells(const glm::dvec2& lo, const glm::dvec2& hi,
                 const std::vector<std::vector<std::uint32_t>>& grid, F&& f) const;
  std::optional<Contact> contact(const Triangle& t, const glm::dvec2& p, double band_lo,
                                 double band_hi) const;
  // Pushes `p` out of walls; false when it cannot be freed.
  bool resolve(glm::dvec2& p, double floor_z) const;
  bool substep(const glm::dvec2& delta);

  NavSettings settings_;
  std::vector<Triangle> walls_;   // solid triangles that may block (anything not facing straight up)
  std::vector<Triangle> floors_;  // solid triangles facing up
  glm::dvec2 grid_origin_{0.0};
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> wall_grid_, floor_grid_;
  mutable std::vector<std::uint32_t> stamp_;  // de-duplicates triangles spanning several grid cells
  mutable std::uint32_t stamp_value_ = 0;

  glm::dvec3 feet_{0.0}, start_{0.0};
  std::uint32_t floor_polygon_ = kNoPolygon, start_polygon_ = kNoPolygon;
  double distance_ = 0.0;
};

}  // namespace walk::kiosk
