// Degenerate cases for every ray-casting predicate: the exact-sign edge function, the watertight triangle
// test, the axial planes' 2D test with its slack, the BSP's plane classification and interval split, the tie
// rule, the self-hit policy, grazing rays, batches and the factory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "compiler/raycast/axial_caster.hpp"
#include "compiler/raycast/brute_force_caster.hpp"
#include "compiler/raycast/embree_caster.hpp"
#include "compiler/raycast/watertight_triangle.hpp"
#include "model/error.hpp"
#include "tests/compiler/test_ray_compare.hpp"

namespace walk::compiler {
namespace test_ray_predicates {  // named, not anonymous: the suite compiles as unity batches

using V = model::Vec3;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Unit square in z = 0 as two triangles (polygon 0), front facing +z.
std::vector<Triangle> square(double z = 0.0, std::uint32_t polygon = 0) {
  return {{V(0, 0, z), V(1, 0, z), V(1, 1, z), polygon}, {V(0, 0, z), V(1, 1, z), V(0, 1, z), polygon}};
}

// The same square rotated off the axes, so it goes to the BSP.
std::vector<Triangle> tilted_square() {
  auto r = [](V p) { return V(p.x, p.y * 0.8 - p.z * 0.6, p.y * 0.6 + p.z * 0.8); };
  return {{r(V(0, 0, 0)), r(V(1, 0, 0)), r(V(1, 1, 0)), 0}, {r(V(0, 0, 0)), r(V(1, 1, 0)), r(V(0, 1, 0)), 0}};
}

TEST(RayPredicates, DiffOfProductsHasTheExactSign) {
  EXPECT_EQ(diff_of_products(3.0, 5.0, 5.0, 3.0), 0.0);
  const double e = std::ldexp(1.0, -52);
  // (1+e)(1-e) - 1*1 = -e^2: lost entirely by the naive formula, kept by the FMA one.
  EXPECT_EQ((1.0 + e) * (1.0 - e) - 1.0 * 1.0, 0.0);
  EXPECT_LT(diff_of_products(1.0 + e, 1.0 - e, 1.0, 1.0), 0.0);
  EXPECT_GT(diff_of_products(1.0, 1.0, 1.0 + e, 1.0 - e), 0.0);
}

TEST(RayPredicates, WatertightThroughSharedEdgeAndVertex) {
  const auto sq = square();
  auto hits = [&](V o, V d) {
    const ShearedRay r(o, d);
    int n = 0;
    for (const auto& t : sq) {
      double th = 0.0;
      n += intersect_watertight(r, t.a, t.b, t.c, 0.0, kInf, th) ? 1 : 0;
    }
    return n;
  };
  EXPECT_GE(hits(V(0.3, 0.3, 1), V(0.4, 0.4, -2)), 1);      // through the shared diagonal's midpoint
  EXPECT_GE(hits(V(0.1, 0.9, 1), V(-0.1, -0.9, -1)), 1);    // exactly at the shared vertex (0,0)
  EXPECT_EQ(hits(V(0.5, 0.5, 1), V(0.0, 0.0, 1.0)), 0);     // pointing away
  EXPECT_EQ(hits(V(-0.5, 0.5, 0), V(1.0, 0.0, 0.0)), 0);    // in the plane: no area, no hit
  EXPECT_EQ(hits(V(1.0 + 1e-12, 0.5, 1), V(0, 0, -1)), 0);  // just outside the outer edge
}

TEST(RayPredicates, WatertightRejectsDegenerateInput) {
  const ShearedRay zero(V(0, 0, 1), V(0, 0, 0));
  EXPECT_FALSE(zero.valid);
  const ShearedRay nan(V(0, 0, 1), V(0, std::nan(""), -1));
  EXPECT_FALSE(nan.valid);
  const ShearedRay r(V(0.2, 0.2, 1), V(0, 0, -1));
  double t = 0.0;
  EXPECT_FALSE(intersect_watertight(r, V(0, 0, 0), V(1, 1, 0), V(2, 2, 0), 0.0, kInf, t));  // collinear
  EXPECT_TRUE(intersect_watertight(r, V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), 0.0, kInf, t));
  EXPECT_DOUBLE_EQ(t, 1.0);
  EXPECT_FALSE(intersect_watertight(r, V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), 1.0, kInf, t));  // t == tmin
  EXPECT_FALSE(intersect_watertight(r, V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), 0.0, 1.0, t));   // t == tmax
  EXPECT_TRUE(intersect_watertight(r, V(0, 0, 0), V(0, 1, 0), V(1, 0, 0), 0.0, kInf, t));   // back side
}

TEST(RayPredicates, AxialEdgeSlackIsOneNanometre) {
  const AxialCaster c(square());
  EXPECT_EQ(c.planes().stats().rectangles, 1u);  // the two halves merged
  auto hit = [&](double x) { return c.closest({V(x, 0.5, 1), V(0, 0, -1)}).hit(); };
  EXPECT_TRUE(hit(1.0));
  EXPECT_TRUE(hit(1.0 + 0.5 * kEdgeSlack));
  EXPECT_FALSE(hit(1.0 + 3.0 * kEdgeSlack));
  EXPECT_TRUE(hit(0.0));
  EXPECT_FALSE(hit(-3.0 * kEdgeSlack));
  // Diagonal edge of a lone triangle (not merged): the slack holds across it too.
  const AxialCaster tri(std::vector<Triangle>{{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), 0}});
  const double s = 0.5 + 0.3 * kEdgeSlack / std::sqrt(2.0);
  EXPECT_TRUE(tri.closest({V(s, s, 1), V(0, 0, -1)}).hit());
  const double f = 0.5 + 3.0 * kEdgeSlack;
  EXPECT_FALSE(tri.closest({V(f, f, 1), V(0, 0, -1)}).hit());
}

TEST(RayPredicates, AxialGridFindsEachOfThousandsOfTiles) {
  const auto tiles = testing::tiled_plane(60, 0.5, 2.0);
  const AxialCaster c(tiles);
  EXPECT_EQ(c.planes().stats().planes[2], 1u);
  // The plane's 3600 tiles are spread over about 180 block listings of a few dozen each (a tile lying across
  // block edges is listed in each): one lookup and a contiguous scan of bounds, not thousands of tests.
  const auto& listings = c.planes().blocks().stats();
  EXPECT_GT(listings.entries, 100u);
  EXPECT_LT(c.planes().stats().cell_entries, 40 * listings.entries);
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) {
      const auto h = c.closest({V(i * 0.5 + 0.25, j * 0.5 + 0.1, 0), V(0, 0, 1)});
      ASSERT_TRUE(h.hit());
      EXPECT_EQ(h.polygon, static_cast<std::uint32_t>(i * 60 + j));
      EXPECT_DOUBLE_EQ(h.t, 2.0);
    }
  // Every grid line and crossing is covered: no gaps between tiles.
  for (int i = 1; i < 60; ++i) EXPECT_TRUE(c.occluded({V(i * 0.5, i * 0.25, 0), V(0, 0, 1)}));
}

TEST(RayPredicates, SelfHitPolicy) {
  for (const auto& tris : {square(), tilted_square()}) {
    const AxialCaster c(tris);
    const BruteForceCaster b(tris);
    // A point on the surface, leaving it: never its own surface with tmin = self_hit_tmin.
    const V p = (tris[0].a + tris[0].b + tris[0].c) / 3.0;
    const V n = glm::normalize(glm::cross(tris[0].b - tris[0].a, tris[0].c - tris[0].a));
    for (const V d : {n, -n, n + V(0.3, 0.1, 0.0)}) {
      const Ray r{p, d, self_hit_tmin(d), kInf};
      EXPECT_FALSE(c.closest(r).hit());
      EXPECT_FALSE(c.occluded(r));
      EXPECT_FALSE(b.closest(r).hit());
    }
    // The surface 1 cm away is hit.
    const Ray r{p + 0.01 * n, -n, self_hit_tmin(n), kInf};
    EXPECT_TRUE(c.closest(r).hit());
    EXPECT_NEAR(c.closest(r).t, 0.01, 1e-12);
  }
}

TEST(RayPredicates, NegativeTminCountsAsZero) {
  const AxialCaster c(square());
  EXPECT_FALSE(c.closest({V(0.5, 0.5, 1), V(0, 0, 1), -10.0, kInf}).hit());
  EXPECT_FALSE(c.occluded({V(0.5, 0.5, 1), V(0, 0, 1), -10.0, kInf}));
}

TEST(RayPredicates, TieRulePrefersTheFacingCopyThenTheLowerIndex) {
  // Back-to-back duplicates of one wall (two zones), front +z (polygon 0) and front -z (polygon 1).
  std::vector<Triangle> tris = square(0.0, 0);
  for (auto t : square(0.0, 1)) tris.push_back({t.a, t.c, t.b, 1});
  for (const char* name : {"axial", "brute"}) {
    const auto c = make_ray_caster(name, tris);
    const auto down = c->closest({V(0.3, 0.6, 1), V(0, 0, -1)});
    const auto up = c->closest({V(0.3, 0.6, -1), V(0, 0, 1)});
    EXPECT_EQ(down.polygon, 0u) << name;
    EXPECT_TRUE(down.front) << name;
    EXPECT_EQ(up.polygon, 1u) << name;
    EXPECT_TRUE(up.front) << name;
  }
  RayHit best{1.0, 5, 5, false};
  EXPECT_TRUE(better_hit(1.0, true, 9, best, 1e-9));
  EXPECT_TRUE(better_hit(1.0, false, 4, best, 1e-9));
  EXPECT_FALSE(better_hit(1.0, false, 6, best, 1e-9));
  EXPECT_TRUE(better_hit(0.5, false, 6, best, 1e-9));
  EXPECT_FALSE(better_hit(1.5, true, 1, best, 1e-9));
}

// A room: floor, ceiling and four walls of a 4 x 3 x 2.5 box (axial), plus a tilted panel (BSP).
std::vector<Triangle> room() {
  std::vector<Triangle> t;
  std::uint32_t p = 0;
  auto quad = [&](V a, V b, V c, V d) {
    t.push_back({a, b, c, p});
    t.push_back({a, c, d, p++});
  };
  quad(V(0, 0, 0), V(4, 0, 0), V(4, 3, 0), V(0, 3, 0));
  quad(V(0, 0, 2.5), V(0, 3, 2.5), V(4, 3, 2.5), V(4, 0, 2.5));
  quad(V(0, 0, 0), V(0, 3, 0), V(0, 3, 2.5), V(0, 0, 2.5));
  quad(V(4, 0, 0), V(4, 0, 2.5), V(4, 3, 2.5), V(4, 3, 0));
  quad(V(0, 0, 0), V(0, 0, 2.5), V(4, 0, 2.5), V(4, 0, 0));
  quad(V(0, 3, 0), V(4, 3, 0), V(4, 3, 2.5), V(0, 3, 2.5));
  quad(V(1, 1, 0.5), V(2, 1, 0.7), V(2, 2, 0.9), V(1, 2, 0.7));  // tilted
  return t;
}

TEST(RayPredicates, GrazingAlongAWallGivesTheSameAnswerAsNearIt) {
  const auto tris = room();
  const AxialCaster c(tris);
  // Along the floor (in its plane), and 1 mm above it: both meet the far wall x = 4.
  for (const double z : {0.0, 1e-3}) {
    const auto h = c.closest({V(0.5, 0.5, z), V(1, 0.1, 0)});
    ASSERT_TRUE(h.hit()) << z;
    EXPECT_EQ(h.polygon, 3u) << z;
    EXPECT_NEAR(h.t, 3.5, 1e-12);
  }
  // Along the wall y = 0 and the floor at once (the room's lower edge): it meets the wall x = 4 at its
  // corner.
  const auto corner = c.closest({V(0.5, 0.0, 0.0), V(1, 0, 0)});
  ASSERT_TRUE(corner.hit());
  EXPECT_EQ(corner.polygon, 3u);
  // Parallel to an axis plane inside the BSP's node planes: the tilted panel is still found.
  const auto panel = c.closest({V(1.5, 1.5, 2.0), V(0, 0, -1)});
  ASSERT_TRUE(panel.hit());
  EXPECT_EQ(panel.polygon, 6u);
  EXPECT_NEAR(panel.t, 2.0 - 0.7, 1e-12);
}

TEST(RayPredicates, BspSidesAndParallelRays) {
  // Many tilted panels in a row make a deep BSP; rays parallel to the panels, through them and along
  // split planes must agree with brute force.
  std::vector<Triangle> tris;
  for (std::uint32_t i = 0; i < 64; ++i) {
    const double x = i * 0.25;
    tris.push_back({V(x, 0, 0), V(x + 0.1, 1, 0.2), V(x + 0.05, 0, 1), i});
  }
  const AxialCaster c(tris);
  const BruteForceCaster b(tris);
  EXPECT_GT(c.bsp().stats().nodes, 1u);
  std::size_t hits = 0;
  for (int i = 0; i < 400; ++i) {
    const double x = i * 0.04, y = 0.05 + (i % 7) * 0.1;
    for (const V d : {V(1, 0, 0), V(-1, 0, 0), V(0, 1, 0), V(0, 0, 1), V(1, 0.01, 0.02)}) {
      const Ray r{V(x - 0.5 * d.x, y - 0.5 * d.y, 0.3 - 0.5 * d.z), d, 0.0, kInf};
      const auto a = c.closest(r), e = b.closest(r);
      ASSERT_EQ(a.hit(), e.hit()) << i;
      if (a.hit()) {
        ++hits;
        EXPECT_EQ(a.polygon, e.polygon);
        EXPECT_NEAR(a.t, e.t, 1e-12);
      }
      EXPECT_EQ(c.occluded(r), b.occluded(r));
    }
  }
  EXPECT_GT(hits, 100u);
}

TEST(RayPredicates, ZeroAndNonFiniteRaysHitNothing) {
  const auto tris = room();
  for (const auto& name : ray_caster_names()) {
    const auto c = make_ray_caster(name, tris);
    EXPECT_FALSE(c->closest({V(1, 1, 1), V(0, 0, 0)}).hit()) << name;
    EXPECT_FALSE(c->occluded({V(1, 1, 1), V(0, 0, 0)})) << name;
    EXPECT_FALSE(c->closest({V(std::nan(""), 1, 1), V(0, 0, 1)}).hit()) << name;
  }
}

// A floor and a ceiling 100 m across: 50 m from the model's centre a float coordinate is good to 4 um,
// coarser than the 1 um self-hit distance, so plain Embree meets the floor a ray leaves, or the ceiling a
// segment ends on. embree-exact confirms Embree's hits in double and must keep the policy like the double
// casters.
TEST(RayCasterInterface, EmbreeExactKeepsTheSelfHitPolicyFarFromTheCentre) {
  if (!embree_available()) {
    EXPECT_THROW((void)make_ray_caster("embree-exact", room()), Error);
    return;
  }
  std::vector<Triangle> tris = square(0.0, 0);
  for (const auto& t : square(3.0, 1)) tris.push_back({t.a, t.c, t.b, 1});  // the ceiling faces down
  for (auto& t : tris) {
    t.a = V(t.a.x * 100.0, t.a.y * 100.0, t.a.z);
    t.b = V(t.b.x * 100.0, t.b.y * 100.0, t.b.z);
    t.c = V(t.c.x * 100.0, t.c.y * 100.0, t.c.z);
  }
  const auto exact = make_ray_caster("embree-exact", tris);
  const auto plain = make_ray_caster("embree", tris);
  const AxialCaster axial(tris);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> at(90.0, 99.9), up(1e-3, 1.0), turn(0.0, 6.283185307179586);
  int plain_wrong = 0;
  for (int i = 0; i < 20000; ++i) {
    const V p(at(rng), at(rng), 0.0);
    const double z = up(rng), a = turn(rng), r = std::sqrt(1.0 - z * z);
    const V d(r * std::cos(a), r * std::sin(a), z);
    const V q = p + d * (3.0 / d.z);  // where it meets the ceiling's plane
    if (!(q.x > 0.0 && q.x < 100.0 && q.y > 0.0 && q.y < 100.0)) continue;  // out at the open side
    // Leaving the floor by the policy (tmin), and as the solver does (1 um off the surface, tmin 0).
    for (const Ray ray :
         {Ray{p, d, self_hit_tmin(d), kInf}, Ray{p + V(0, 0, kSelfHitDistance), d, 0.0, kInf}}) {
      const RayHit h = exact->closest(ray);
      ASSERT_TRUE(h.hit()) << i;
      ASSERT_EQ(h.polygon, 1u) << i << ": embree-exact met the floor the ray leaves";
      EXPECT_NEAR(h.t, axial.closest(ray).t, 1e-9 * h.t) << i;  // t in double, as the double casters
      plain_wrong += plain->closest(ray).polygon != 1u;
    }
    // A segment from the floor to the ceiling, stopped short of it by the policy: nothing in between.
    const Ray seg{p, q - p, self_hit_tmin(q - p), 1.0 - self_hit_tmin(q - p)};
    ASSERT_FALSE(exact->occluded(seg)) << i;
    ASSERT_FALSE(axial.occluded(seg)) << i;
    plain_wrong += plain->occluded(seg);
  }
  // Not a requirement on Embree, a record of why embree-exact exists: plain Embree breaks the policy here.
  RecordProperty("plain_embree_self_hits", plain_wrong);
}

TEST(RayCasterInterface, FactoryNamesAndErrors) {
  const auto names = ray_caster_names();
  EXPECT_EQ(names[0], "axial");
  EXPECT_EQ(std::find(names.begin(), names.end(), "embree") != names.end(), embree_available());
  EXPECT_THROW((void)make_ray_caster("optix", room()), Error);
  if (!embree_available()) {
    EXPECT_THROW((void)make_ray_caster("embree", room()), Error);
  }
  for (const auto& name : names) {
    const auto c = make_ray_caster(name, room());
    EXPECT_EQ(c->name(), name);
    EXPECT_GT(c->memory_bytes(), 0u);
    const auto h = c->closest({V(2, 1.5, 1.25), V(0, 0, 1)});
    ASSERT_TRUE(h.hit()) << name;
    EXPECT_EQ(h.polygon, 1u) << name;
    EXPECT_NEAR(h.t, 1.25, 1e-6) << name;
    EXPECT_TRUE(h.front) << name;
    EXPECT_FALSE(c->occluded({V(2, 1.5, 1.25), V(0, 0, 1), 0.0, 1.0})) << name;  // ends before the ceiling
  }
  const auto c = make_ray_caster("axial", room());
  std::vector<Ray> rays(3);
  std::vector<RayHit> hits(2);
  EXPECT_THROW(c->closest_batch(rays, hits, 2), Error);
}

TEST(RayCasterInterface, BatchesMatchSingleRaysOnAnyThreadCount) {
  const auto tris = room();
  const auto c = make_ray_caster("axial", tris);
  std::vector<Ray> rays;
  for (int i = 0; i < 5000; ++i) {
    const double a = i * 0.013, b = i * 0.007;
    rays.push_back(
        {V(2, 1.5, 1.2), V(std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b) - 0.3)});
  }
  std::vector<RayHit> single(rays.size());
  std::vector<std::uint8_t> single_any(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    single[i] = c->closest(rays[i]);
    single_any[i] = c->occluded(rays[i]) ? 1 : 0;
  }
  for (const unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<RayHit> hits(rays.size());
    std::vector<std::uint8_t> any(rays.size());
    c->closest_batch(rays, hits, threads);
    c->occluded_batch(rays, any, threads);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(hits[i].triangle, single[i].triangle) << threads;
      ASSERT_EQ(hits[i].t, single[i].t) << threads;
      ASSERT_EQ(any[i], single_any[i]) << threads;
    }
  }
}

}  // namespace test_ray_predicates
}  // namespace walk::compiler
