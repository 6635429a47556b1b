#pragma once
// Test scene: two 4 x 4 x 3 m rooms side by side along x (A: 0..4, B: 4..8) joined by a 1 x 2.2 m opening in
// the shared wall at y 1.5..2.5. Each room has its own albedo; two circuits light them unequally. Radiosity
// is constant over each polygon, so a pixel's expected colour follows from the display formula alone.
#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <memory>
#include <string>

#include "model/bundle.hpp"

namespace walk::render::test {

struct TwoRooms {
  glm::dvec3 albedo_a{0.7, 0.7, 0.7};
  glm::dvec3 albedo_b{0.2, 0.5, 0.8};
  // Irradiance-like scale per room per circuit: L[v][c] = albedo * circuit_x[c] * factor(polygon).
  double circuit_a[2] = {60.0, 5.0};
  double circuit_b[2] = {10.0, 50.0};
  double floor_factor = 1.0;
  double ceiling_factor = 0.6;
  double wall_factor = 0.8;
  float ambient = 8.0f;
  float exposure = 100.0f;
  bool glass_door = false;    // true: the doorway holds a glass polygon instead of an opening
  bool cell_a_sees_b = true;  // false: room B's polygons are left out of cell A's PVS
  int subdivisions = 1;       // each rectangle as an n x n grid of quads
  int circuits = 2;           // more than 2: extra circuits with no light (for the limit test)
  // Vertex light scaled by 0.4 .. 1.6 along each rectangle's first edge (mean 1 over the grid's vertices),
  // so per-vertex patches differ from the flat polygon light of the coarse level. Needs subdivisions >= 2.
  bool light_gradient = false;
  // Vertex light scaled 1.6 and 0.4 in a checkerboard over the grid: with one quad per rectangle, opposite
  // corners match, so Gouraud triangles show 1.6 along the diagonal where the bilinear patch has 1.0.
  bool light_twist = false;
  // The checkerboard on the columns i < n/2 only (needs subdivisions >= 4): those quads are subdivided, their
  // neighbours are not, so the refined picture has T-junctions along the boundary.
  bool light_twist_half = false;
  // Four cells (each room halved at y = 2) under a three-node tree; each room's PVS leaves out the other
  // room's copy of the shared wall, which faces away from it: conservative, and smaller than everything.
  bool four_cells = false;
  // A 0.5 m crate (five faces, each its own polygon) in room B's corner behind the shared wall, hidden from
  // most of room A: what occlusion culling should leave out.
  bool crate = false;
  // Write the coarse form (CIDX/CRNG): each rectangle as two triangles over its grid's corner vertices.
  bool coarse_form = false;
};

[[nodiscard]] model::BundleContents make_two_rooms(const TwoRooms& scene);
// This process's folder for the files tests write, made on first use and removed at exit: ctest runs each
// test in a process of its own, and a folder per process left behind piled up in /tmp by the thousand.
[[nodiscard]] const std::filesystem::path& test_folder();
// Writes the scene to a unique temporary file and opens it.
[[nodiscard]] std::unique_ptr<model::Bundle> open_two_rooms(const TwoRooms& scene, const std::string& name);
// Writes any contents the same way (a scene edited after make_two_rooms).
[[nodiscard]] std::unique_ptr<model::Bundle> open_bundle(const model::BundleContents& contents,
                                                         const std::string& name);

// Expected 8-bit display value of a linear radiosity (W/m2) under `exposure`: clamp, sRGB encode, round.
[[nodiscard]] int expected_byte(double radiosity, double exposure);
// Linear radiosity of a polygon in a room at the given circuit levels.
[[nodiscard]] glm::dvec3 radiosity(const TwoRooms& scene, bool room_b, double factor, double level0,
                                   double level1);

}  // namespace walk::render::test
