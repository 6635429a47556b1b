// The single-occluder test (visibility/occluders.hpp) at its degenerate cases, and a trace that passes a
// back face must not skip the front copy a rounding behind it.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "compiler/raycast/ray_caster.hpp"
#include "compiler/visibility/occluders.hpp"
#include "compiler/visibility/trace_through_glass.hpp"

namespace walk::compiler {
namespace test_occluders {  // named, not anonymous: the suite compiles as unity batches

using V = model::Vec3;

// A square in the plane y = y0, x and z in [lo, hi], facing -y (towards a light at smaller y).
Occluder wall(double y0, double lo, double hi) {
  // Counter-clockwise about -y.
  const auto o = make_occluder({V(lo, y0, lo), V(hi, y0, lo), V(hi, y0, hi), V(lo, y0, hi)}, V(0, -1, 0));
  EXPECT_TRUE(o.has_value());
  EXPECT_NEAR(o->plane.d, y0, 1e-12);
  EXPECT_NEAR(o->area, (hi - lo) * (hi - lo), 1e-12);
  return o.value();  // throws (the test fails) when there is none
}

Winding square_at(double y, double cx, double cz, double half) {
  return {V(cx - half, y, cz - half), V(cx + half, y, cz - half), V(cx + half, y, cz + half),
          V(cx - half, y, cz + half)};
}

TEST(Occluders, WallHidesWhatLiesWhollyInItsUmbra) {
  const Occluder o = wall(0.0, -2.0, 2.0);
  const Winding light = square_at(-1.0, 0.0, 0.0, 0.5);
  EXPECT_TRUE(hidden_by(square_at(1.0, 0.0, 0.0, 0.5), light, o, true));
  // Partly outside the umbra (x <= 2 + 1.5 y): a sight line from the light passes the wall's edge.
  EXPECT_FALSE(hidden_by(square_at(1.0, 3.3, 0.0, 0.5), light, o, true));  // x up to 3.8 > 3.5
  // A light narrower than the wall: the umbra widens behind it (its sides run from the light's edges
  // through the wall's, x = 2 + 1.5 y), so a target far behind is hidden too.
  EXPECT_TRUE(hidden_by(square_at(10.0, 0.0, 0.0, 0.5), light, o, true));
  // A light wider than the wall (6 m against 4 m): the umbra closes 2 m behind it (x = +-(2 - y)).
  const Winding wide = square_at(-1.0, 0.0, 0.0, 3.0);
  EXPECT_TRUE(hidden_by(square_at(1.0, 0.0, 0.0, 0.5), wide, o, true));
  EXPECT_FALSE(hidden_by(square_at(1.0, 0.0, 0.0, 1.2), wide, o, true));
  EXPECT_FALSE(hidden_by(square_at(10.0, 0.0, 0.0, 0.1), wide, o, true));
}

TEST(Occluders, DegenerateContactsKeepTheTarget) {
  const Occluder o = wall(0.0, -2.0, 2.0);
  const Winding light = square_at(-1.0, 0.0, 0.0, 0.5);
  // A target in the occluder's plane, or touching it, or straddling it.
  EXPECT_FALSE(hidden_by(square_at(0.0, 0.0, 0.0, 0.5), light, o, true));
  EXPECT_FALSE(hidden_by({V(0, 0, 0), V(1, 1, 0), V(0, 1, 1)}, light, o, true));
  EXPECT_FALSE(hidden_by({V(0, -0.5, 0), V(0.5, 0.5, 0), V(0, 0.5, 0.5)}, light, o, true));
  // A light touching the occluder's plane, or straddling it.
  EXPECT_FALSE(hidden_by(square_at(1.0, 0.0, 0.0, 0.5), {V(0, 0, 0), V(0.5, -1, 0), V(0, -1, 0.5)}, o, true));
  EXPECT_FALSE(
      hidden_by(square_at(1.0, 0.0, 0.0, 0.5), {V(0, 0.5, 0), V(0.5, -1, 0), V(0, -1, 0.5)}, o, true));
  // Sight lines through the occluder's very edge (within kPlaneEpsilon) are not blocked.
  const Winding edge_light = square_at(-1.0, 1.0, 0.0, 1.0);  // x up to 2.0, the wall's edge
  EXPECT_FALSE(hidden_by(square_at(1.0, 2.0, 0.0, 1e-6), edge_light, o, true));
  // Empty windings hide nothing and are hidden by nothing.
  EXPECT_FALSE(hidden_by({}, light, o, true));
  EXPECT_FALSE(hidden_by(square_at(1.0, 0.0, 0.0, 0.5), {}, o, true));
}

TEST(Occluders, BackFacesBlockOnlyWhenDrawnFromBothSides) {
  const Occluder o = wall(0.0, -2.0, 2.0);              // faces -y
  const Winding light = square_at(1.0, 0.0, 0.0, 0.5);  // behind it
  const Winding target = square_at(-1.0, 0.0, 0.0, 0.5);
  EXPECT_FALSE(hidden_by(target, light, o, true)) << "culled from behind: sight lines pass";
  EXPECT_TRUE(hidden_by(target, light, o, false)) << "two-sided: it blocks";
}

TEST(Occluders, OnlyConvexPlanarOpaquePolygonsOccludeLargestFirst) {
  Partition part;
  part.cells.push_back({V(-10.0), V(10.0)});
  std::vector<VisPolygon> polys(4);
  auto quad = [](VisPolygon& p, std::vector<V> pts, bool opaque) {
    p.opaque = opaque;
    p.normal = glm::normalize(glm::cross(pts[1] - pts[0], pts[2] - pts[0]));
    p.hull = pts;
    p.triangles = {{pts[0], pts[1], pts[2]}, {pts[0], pts[2], pts[3]}};
  };
  quad(polys[0], {V(0, 0, 0), V(2, 0, 0), V(2, 0, 2), V(0, 0, 2)}, true);   // 4 m^2
  quad(polys[1], {V(0, 1, 0), V(3, 1, 0), V(3, 1, 3), V(0, 1, 3)}, true);   // 9 m^2
  quad(polys[2], {V(0, 2, 0), V(3, 2, 0), V(3, 2, 3), V(0, 2, 3)}, false);  // glass
  // An L shape: its hull is larger than its triangles.
  polys[3].opaque = true;
  polys[3].normal = V(0, -1, 0);
  polys[3].hull = {V(0, 3, 0), V(2, 3, 0), V(2, 3, 2), V(0, 3, 2)};
  polys[3].triangles = {{V(0, 3, 0), V(2, 3, 0), V(2, 3, 1)}, {V(0, 3, 0), V(0, 3, 2), V(1, 3, 2)}};
  part.cell_polygons.push_back({0, 1, 2, 3});
  // No occluder from fewer than three points or an edge of no length.
  EXPECT_FALSE(make_occluder({V(0, 0, 0), V(1, 0, 0)}, V(0, -1, 0)).has_value());
  EXPECT_FALSE(make_occluder({V(0, 0, 0), V(0, 0, 0), V(1, 0, 1)}, V(0, -1, 0)).has_value());
  const auto occ = cell_occluders(part, polys);
  ASSERT_EQ(occ.size(), 1u);
  ASSERT_EQ(occ[0].size(), 2u);
  EXPECT_NEAR(occ[0][0].area, 9.0, 1e-9);
  EXPECT_NEAR(occ[0][1].area, 4.0, 1e-9);
}

TEST(Occluders, TracePastABackFaceFindsTheFrontCopyARoundingBehind) {
  // Two copies of a wall, back to back: the one facing the ray 40 nm behind the one facing away.
  const double gap = 4e-8;
  std::vector<Triangle> tris;
  auto square = [&](double y, bool facing_minus_y, std::uint32_t polygon) {
    const V a(-1, y, -1), b(1, y, -1), c(1, y, 1), d(-1, y, 1);
    if (facing_minus_y) {  // cross(b - a, c - a) = (0, -4, 0)
      tris.push_back({a, b, c, polygon});
      tris.push_back({a, c, d, polygon});
    } else {
      tris.push_back({a, c, b, polygon});
      tris.push_back({a, d, c, polygon});
    }
  };
  square(1.0, false, 0);       // faces +y: met from behind
  square(1.0 + gap, true, 1);  // faces -y: met from the front
  square(3.0, true, 2);        // a window behind the wall (glass)
  const std::vector<char> glass{0, 0, 1};
  for (const char* name : {"axial", "brute"}) {
    const auto caster = make_ray_caster(name, tris);
    std::vector<std::uint32_t> ids;
    const RayHit h = trace_through_glass(*caster, {V(0.1, 0, 0.2), V(0.05, 1, -0.03)}, glass, ids, true);
    ASSERT_TRUE(h.hit()) << name;
    EXPECT_EQ(h.polygon, 1u) << name << ": the front copy stops the sight line";
    EXPECT_EQ(ids, std::vector<std::uint32_t>{1}) << name;
  }
}

}  // namespace test_occluders
}  // namespace walk::compiler
