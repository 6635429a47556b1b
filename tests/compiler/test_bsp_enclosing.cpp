// The BSP's enclosing node (PolygonBsp::enclosing) and common ancestor: a segment inside a box must meet the
// same triangles searched from the node enclosing the box as from the root. The boxes include ones lying
// exactly on the tree's axis split planes, flat ones in those planes, ones just off a triangle's own plane
// and ones in empty space.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "compiler/raycast/local_triangles.hpp"
#include "compiler/raycast/polygon_bsp.hpp"
#include "tests/compiler/test_ray_compare.hpp"

namespace walk::compiler {
namespace test_bsp_enclosing {  // named, not anonymous: the suite compiles as unity batches

using V = model::Vec3;
using testing::random_unit;

// The planes x, y, z = 1, 2, 3: the root's axis split candidates (quarters of the bounds [0, 4]^3).
constexpr double kQuarters[] = {1.0, 2.0, 3.0};

// Slanted triangles through [0, 4]^3 (exactly its bounds), some of them large; a fan of ones sharing the
// plane z = x; and, for each quarter plane, triangles with an edge lying in it, on either side of it.
std::vector<Triangle> slanted_scene() {
  std::vector<Triangle> tris;
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> pos(0.0, 4.0), size(0.1, 1.5);
  std::uint32_t polygon = 0;
  const auto in_bounds = [](const V& p) { return glm::clamp(p, V(0.0), V(4.0)); };
  for (int i = 0; i < 300; ++i) {
    const V p(pos(rng), pos(rng), pos(rng));
    const double s = size(rng);
    tris.push_back({p, in_bounds(p + s * random_unit(rng)), in_bounds(p + s * random_unit(rng)), polygon++});
  }
  for (int i = 0; i < 8; ++i) {
    const double y = 0.5 * i;
    tris.push_back({V(0, y, 0), V(4, y + 0.4, 4), V(2, y + 0.5, 2) + V(0.5, 0, 0.5), polygon++});
  }
  for (int k = 0; k < 3; ++k)
    for (const double q : kQuarters)
      for (int i = 0; i < 8; ++i) {
        V a(pos(rng), pos(rng), pos(rng)), b = in_bounds(a + 0.4 * random_unit(rng));
        // The edge in the plane, or (i >= 4) poking 0.5 nm through it: within kPlaneEps, so the tree keeps
        // the triangle on the side of its third vertex only.
        const double side = i % 2 == 0 ? -1.0 : 1.0;
        a[k] = b[k] = i < 4 ? q : q - side * 5e-10;
        V c = in_bounds(0.5 * (a + b) + 0.3 * random_unit(rng));
        c[k] = q + side * 0.3;
        tris.push_back({a, b, c, polygon++});
      }
  return tris;
}

// The scene in the local frame and a BSP over all of it (the tree reads the triangles during its searches).
struct SlantedBsp {
  std::vector<Triangle> tris = slanted_scene();
  LocalTriangles local{tris};
  PolygonBsp bsp{local, all_ids(tris.size())};

  static std::vector<std::uint32_t> all_ids(std::size_t n) {
    std::vector<std::uint32_t> ids(n);
    for (std::uint32_t i = 0; i < n; ++i) ids[i] = i;
    return ids;
  }
};

struct Segment {
  V origin, dir;
  double tmin, tmax;
};

// Segments inside the box: between two random points of it, and from one towards a triangle's vertex in it.
std::vector<Segment> segments_in(const V& lo, const V& hi, const LocalTriangles& local,
                                 std::mt19937_64& rng) {
  std::uniform_real_distribution<double> w(0.0, 1.0);
  auto point = [&] { return lo + V(w(rng), w(rng), w(rng)) * (hi - lo); };
  std::vector<Segment> out;
  for (int i = 0; i < 40; ++i) {
    const V a = point(), b = point();
    if (a != b) out.push_back({a, b - a, 0.0, 1.0});
  }
  for (const Triangle& t : local.triangles)
    for (const V& v : {t.a, t.b, t.c})
      if (glm::all(glm::greaterThanEqual(v, lo)) && glm::all(glm::lessThanEqual(v, hi))) {
        const V a = point();
        if (a != v) out.push_back({a, v - a, 0.0, 1.0});
      }
  return out;
}

TEST(BspEnclosing, SearchFromTheEnclosingNodeFindsWhatTheRootSearchFinds) {
  const SlantedBsp scene;
  const auto& [tris, local, bsp] = scene;
  ASSERT_GT(bsp.stats().axis_splits, 0u);
  ASSERT_GT(bsp.stats().depth, 4);

  // Boxes in the local frame: random ones of several sizes, ones with a face on a quarter plane of the
  // bounds (where the tree's axis splits are), flat ones in such a plane, and ones 1e-12 off the fan's plane.
  std::mt19937_64 rng(78);
  std::uniform_real_distribution<double> pos(0.0, 4.0), side(0.01, 1.0);
  const V c = local.centre;
  std::vector<std::pair<V, V>> boxes;
  for (int i = 0; i < 300; ++i) {
    const V lo(pos(rng), pos(rng), pos(rng));
    const double s = side(rng);
    boxes.emplace_back(lo - c, lo + V(s) - c);
  }
  // Around the vertices lying in the quarter planes: faces on the plane on either side, and flat in it.
  std::vector<V> on_plane[3];
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k)
      for (const double q : kQuarters)
        if (t.a[k] == t.b[k] && std::abs(t.a[k] - q) < 1e-9)
          on_plane[k].insert(on_plane[k].end(), {t.a, t.b});
  for (int k = 0; k < 3; ++k) {
    ASSERT_GE(on_plane[k].size(), 30u);
    for (int i = 0; i < 300; ++i) {
      const double s = side(rng);
      const V v = on_plane[k][rng() % on_plane[k].size()];
      const double q = std::round(v[k]);
      V lo = v - V(0.3 * s), hi = lo + V(s);
      if (i % 5 == 0) lo[k] = q, hi[k] = q + s;          // a face on the plane, box on its upper side
      if (i % 5 == 1) lo[k] = q - s, hi[k] = q;          // a face on the plane, box on its lower side
      if (i % 5 == 2) lo[k] = hi[k] = q;                 // flat, in the plane
      if (i % 5 == 3) lo[k] = q + 2e-10, hi[k] = q + s;  // off the plane by less than kPlaneEps
      if (i % 5 == 4) lo[k] = q - s, hi[k] = q - 2e-10;
      boxes.emplace_back(lo - c, hi - c);
    }
  }
  for (int i = 0; i < 30; ++i) {  // just above the plane z = x of the fan, not touching it
    const double x = pos(rng), y = pos(rng);
    boxes.emplace_back(V(x, y, x + 1e-12) - c, V(x + 0.1, y + 0.2, x + 0.1 + 1e-12) - c);
  }

  std::size_t below_root = 0, empty = 0, segments = 0, hits = 0;
  for (const auto& [lo, hi] : boxes) {
    const std::uint32_t start = bsp.enclosing(lo, hi);
    if (start != 0 && start != kNoHit) ++below_root;
    if (start == kNoHit) ++empty;
    for (const Segment& s : segments_in(lo, hi, local, rng)) {
      ++segments;
      RayHit from_root, from_start;
      const double tie = tie_tolerance(s.dir);
      bsp.closest(s.origin, s.dir, s.tmin, s.tmax, tie, from_root);
      const bool any_root = bsp.occluded(s.origin, s.dir, s.tmin, s.tmax);
      if (start == kNoHit) {
        EXPECT_FALSE(from_root.hit()) << "a box the tree calls empty holds a hit";
        continue;
      }
      bsp.closest(s.origin, s.dir, s.tmin, s.tmax, tie, from_start, start);
      EXPECT_EQ(from_root.hit(), from_start.hit()) << "from node " << start;
      EXPECT_EQ(any_root, bsp.occluded(s.origin, s.dir, s.tmin, s.tmax, start));
      if (from_root.hit() && from_start.hit()) {
        ++hits;
        EXPECT_EQ(from_root.triangle, from_start.triangle);
        EXPECT_EQ(from_root.t, from_start.t);
      }
    }
  }
  // Not vacuous: most boxes start below the root, and many segments hit.
  EXPECT_GT(below_root, boxes.size() / 2);
  EXPECT_GT(hits, segments / 10);
  std::printf("enclosing: %zu of %zu boxes below the root, %zu empty, %zu segments, %zu hits\n", below_root,
              boxes.size(), empty, segments, hits);
}

TEST(BspEnclosing, CommonAncestor) {
  const SlantedBsp scene;
  const auto& [tris, local, bsp] = scene;
  const V c = local.centre;
  const std::uint32_t a = bsp.enclosing(V(0.1) - c, V(0.2) - c);
  const std::uint32_t b = bsp.enclosing(V(3.8) - c, V(3.9) - c);
  ASSERT_NE(a, kNoHit);
  ASSERT_NE(b, kNoHit);
  ASSERT_NE(a, b);
  const std::uint32_t none[] = {kNoHit, kNoHit};
  EXPECT_EQ(bsp.common_ancestor({}), kNoHit);
  EXPECT_EQ(bsp.common_ancestor(none), kNoHit);
  const std::uint32_t one[] = {kNoHit, a, a};
  EXPECT_EQ(bsp.common_ancestor(one), a);
  const std::uint32_t with_root[] = {a, 0};
  EXPECT_EQ(bsp.common_ancestor(with_root), 0u);
  // The node enclosing a box that spans both small boxes holds both in its subtree: it is their common
  // ancestor or above it.
  const std::uint32_t ab[] = {a, b};
  const std::uint32_t lca = bsp.common_ancestor(ab);
  EXPECT_NE(lca, a);
  EXPECT_NE(lca, b);
  const std::uint32_t spanning = bsp.enclosing(V(0.1) - c, V(3.9) - c);
  ASSERT_NE(spanning, kNoHit);
  const std::uint32_t both[] = {lca, spanning};
  EXPECT_EQ(bsp.common_ancestor(both), spanning);
  const std::uint32_t ba[] = {b, a, b};
  EXPECT_EQ(bsp.common_ancestor(ba), lca);
}

}  // namespace test_bsp_enclosing
}  // namespace walk::compiler
