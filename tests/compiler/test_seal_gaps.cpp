// Sealing slits between coplanar faces: what is filled, what is left open, and the real house's floors.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>
#include <string>

#include "compiler/geometry/mesher.hpp"
#include "compiler/geometry/openings.hpp"
#include "compiler/geometry/seal_gaps.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {
namespace test_seal_gaps {  // named, not anonymous: the suite compiles as unity batches

using model::Polygon;
using model::Vec3;

Polygon face(std::vector<Vec3> v) {
  Polygon p;
  p.vertices = std::move(v);
  p.role = model::Role::Opaque;
  return p;
}

// Every face's triangles, for casting rays at them.
std::unique_ptr<RayCaster> caster_of(const model::Model& m) {
  std::vector<Triangle> triangles;
  for (std::uint32_t i = 0; i < m.polygons.size(); ++i) {
    const PolygonMesh mesh = mesh_polygon(m.polygons[i], 0.0);
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3)
      triangles.push_back({mesh.vertices[mesh.triangles[t]], mesh.vertices[mesh.triangles[t + 1]],
                           mesh.vertices[mesh.triangles[t + 2]], i});
  }
  return make_ray_caster("brute", triangles);
}

// Of `n` x `n` vertical rays down through [x0, x1] x [y0, y1] from 1 m above height z, how many pass it:
// their first hit lies below z, or there is none.
int rays_through(const RayCaster& caster, double x0, double x1, double y0, double y1, double z, int n) {
  int through = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Ray r;
      r.origin = {x0 + (x1 - x0) * (i + 0.5) / n, y0 + (y1 - y0) * (j + 0.5) / n, z + 1.0};
      r.dir = {0.0, 0.0, -1.0};
      const RayHit h = caster.closest(r);
      through += !h.hit() || h.t > 1.0 + 1e-6 ? 1 : 0;
    }
  return through;
}

// Two floors whose shared edge one of them cuts straight across while the other follows a bend, as the
// house's four-corner floors do: a wedge slit up to 10 mm wide between them.
TEST(SealGaps, FillsTheWedgeBetweenTwoFloors) {
  model::Model m;
  m.polygons.push_back(face({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 0.99, 0}, {0, 1, 0}}));  // bent edge
  m.polygons.push_back(face({{0, 1, 0}, {2, 1, 0}, {2, 2, 0}, {0, 2, 0}}));                // straight
  const auto before = caster_of(m);
  EXPECT_GT(rays_through(*before, 0.0, 2.0, 0.98, 1.02, 0.0, 200), 0) << "the slit lets rays through";
  const SealStats s = seal_gaps(m, 0.03);
  EXPECT_EQ(s.planes, 1u);
  EXPECT_EQ(s.faces_added, 1u);
  // The slit is a triangle 2 m long and 10 mm high at its middle: 0.01 m^2.
  EXPECT_NEAR(s.area, 0.01, 1e-5);
  ASSERT_EQ(m.polygons.size(), 3u);
  EXPECT_EQ(m.polygons[2].role, model::Role::Opaque);
  EXPECT_EQ(m.polygons[2].name.rfind("seal:", 0), 0u);
  const auto after = caster_of(m);
  EXPECT_EQ(rays_through(*after, 0.0, 2.0, 0.98, 1.02, 0.0, 400), 0) << "sealed";
  // The fill faces the way the floors do.
  EXPECT_GT(model::area_vector(m.polygons[2].vertices).z, 0.0);
}

TEST(SealGaps, LeavesOpeningsWiderThanTheWidthAndOtherPlanesAlone) {
  model::Model m;
  // A wall in two pieces with a 0.8 m door between them, and two floors 20 mm apart (a wider "slit").
  m.polygons.push_back(face({{0, 0, 0}, {1, 0, 0}, {1, 0, 2}, {0, 0, 2}}));
  m.polygons.push_back(face({{1.8, 0, 0}, {3, 0, 0}, {3, 0, 2}, {1.8, 0, 2}}));
  m.polygons.push_back(face({{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}));
  m.polygons.push_back(face({{1.02, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1.02, 2, 0}}));
  // A ceiling 1 m above, facing down, with a 5 mm slit: a plane of its own.
  m.polygons.push_back(face({{0, 1, 1}, {0, 2, 1}, {1, 2, 1}, {1, 1, 1}}));
  m.polygons.push_back(face({{1.005, 1, 1}, {1.005, 2, 1}, {2, 2, 1}, {2, 1, 1}}));
  const SealStats s = seal_gaps(m, 0.015);
  EXPECT_EQ(s.faces_added, 1u) << "only the ceiling's 5 mm slit";
  ASSERT_EQ(m.polygons.size(), 7u);
  EXPECT_LT(model::area_vector(m.polygons[6].vertices).z, 0.0) << "facing down like the ceiling";
  EXPECT_NEAR(s.area, 0.005, 1e-5);
}

TEST(SealGaps, OppositeFacingsAndGlassAreNotSealedTogether) {
  model::Model m;
  m.polygons.push_back(face({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));          // up
  m.polygons.push_back(face({{1.005, 0, 0}, {1.005, 1, 0}, {2, 1, 0}, {2, 0, 0}}));  // down
  m.polygons.push_back(face({{2.005, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2.005, 1, 0}}));  // up, glass
  m.polygons[2].role = model::Role::Glass;
  const SealStats s = seal_gaps(m, 0.03);
  EXPECT_EQ(s.faces_added, 0u);
  EXPECT_EQ(m.polygons.size(), 3u);
  EXPECT_EQ(seal_gaps(m, 0.0).planes, 0u) << "width 0: nothing to do";
}

// The shared house: its floors and ceilings are EnergyPlus faces of four corners, cut straight across the
// bent wall line between two rooms. Before sealing, vertical rays along that line pass through the floors.
TEST(SealGaps, HouseFloorsAreClosedAlongTheBentWall) {
  const std::string path = std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf";
  model::Model m = read_dxf(path);
  // Only the horizontal faces (floors, ceilings, roofs, the shading's slabs): the test looks down.
  std::erase_if(m.polygons, [](const Polygon& p) {
    for (const auto& v : p.vertices)
      if (v.z != p.vertices.front().z) return true;
    return false;
  });
  for (auto& p : m.polygons) p.role = model::Role::Opaque;
  // The bend runs from (-3.73, -1.496) to (-2.43, -1.485) to (-1.75, -1.476) at every floor level.
  const auto floors = [&](const model::Model& mm) {
    const auto caster = caster_of(mm);
    int through = 0;
    for (const double z : {2.8, 5.8}) through += rays_through(*caster, -3.7, -1.8, -1.50, -1.47, z, 300);
    return through;
  };
  const int open = floors(m);
  EXPECT_GT(open, 100) << "rays pass between the rooms' floors";
  const SealStats s = seal_gaps(m, 0.03);
  EXPECT_GT(s.faces_added, 0u);
  EXPECT_EQ(floors(m), 0) << "sealed, " << s.summary();
}

}  // namespace test_seal_gaps
}  // namespace walk::compiler
