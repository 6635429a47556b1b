// Degenerate cases of the axial walk's blocks (PlaneBlocks): rays starting exactly on block edges and
// corners, rays lying in a block face, rays aimed at block corners from outside and from far away, and flat
// models with one layer of blocks. Each must give the brute-force answer.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <random>

#include "compiler/raycast/axial_caster.hpp"
#include "compiler/raycast/brute_force_caster.hpp"
#include "tests/compiler/test_ray_compare.hpp"

namespace walk::compiler {
namespace test_plane_blocks {  // named, not anonymous: the suite compiles as unity batches

using V = model::Vec3;
using testing::random_unit;
// Denser than the default, and with no limit from the plane count, so that rays meet many block edges in
// these small models.
constexpr BlockSizing kTestBlocks{.per_element = 0.3, .planes_per_layer = 0.0};

// Walls of 0.5 m quads over [0, n]^3 on the planes x, y, z = c for each c in `at` (default 0..n): a lattice
// of closed boxes, so the blocks' edges fall everywhere relative to the walls.
std::vector<Triangle> cube_lattice(int n, std::vector<double> at = {}) {
  if (at.empty())
    for (int c = 0; c <= n; ++c) at.push_back(c);
  std::vector<Triangle> tris;
  std::uint32_t polygon = 0;
  for (int k = 0; k < 3; ++k)
    for (const double c : at)
      for (int a = 0; a < 2 * n; ++a)
        for (int b = 0; b < 2 * n; ++b, ++polygon) {
          auto p = [&](double u, double v) {
            V q;
            q[k] = c;
            q[(k + 1) % 3] = 0.5 * u;
            q[(k + 2) % 3] = 0.5 * v;
            return q;
          };
          tris.push_back({p(a, b), p(a + 1, b), p(a + 1, b + 1), polygon});
          tris.push_back({p(a, b), p(a + 1, b + 1), p(a, b + 1), polygon});
        }
  return tris;
}

// Closest hits agree in polygon, or in t within the tie distance (two walls meeting on the ray's path); a
// ray passing within rounding of a polygon's edge (aimed at the lattice's own corner, say) is an edge case
// where both answers are right, counted apart.
struct Tally {
  int checked = 0, edge_cases = 0;
};

void expect_same(const RayCaster& ours, const RayCaster& reference, std::span<const Triangle> tris,
                 const Ray& r, Tally& tally) {
  ++tally.checked;
  const RayHit a = ours.closest(r), b = reference.closest(r);
  const bool any_a = ours.occluded(r), any_b = reference.occluded(r);
  const bool agree = a.hit() == b.hit() && any_a == any_b &&
                     (!a.hit() || a.polygon == b.polygon || std::abs(a.t - b.t) <= testing::kTieCheck);
  if (agree) return;
  if (testing::near_edge(tris, r, a) || testing::near_edge(tris, r, b)) {
    ++tally.edge_cases;
    return;
  }
  ADD_FAILURE() << "origin " << r.origin.x << " " << r.origin.y << " " << r.origin.z << " dir " << r.dir.x
                << " " << r.dir.y << " " << r.dir.z << ": ours " << a.hit() << " t " << a.t << " polygon "
                << a.polygon << " any " << any_a << ", reference " << b.hit() << " t " << b.t << " polygon "
                << b.polygon << " any " << any_b;
}

TEST(PlaneBlocks, RaysFromBlockEdgesAndCornersMatchBruteForce) {
  const auto tris = cube_lattice(4);
  const AxialCaster ours(tris, kTestBlocks);
  const BruteForceCaster reference(tris);
  const V centre = whole_metre_centre(tris);
  const PlaneBlocks& blocks = ours.planes().blocks();
  for (int k = 0; k < 3; ++k) ASSERT_GT(blocks.edges(k).size(), 2u) << "want several layers on axis " << k;
  std::mt19937_64 rng(5);
  Tally tally;
  const auto& ex = blocks.edges(0);
  const auto& ey = blocks.edges(1);
  const auto& ez = blocks.edges(2);
  // Interior corners: the grid's outer corners lie within 1e-8 m of the lattice's own outer walls and edges,
  // where every ray is an edge case.
  for (std::size_t i = 1; i + 1 < ex.size(); ++i)
    for (std::size_t j = 1; j + 1 < ey.size(); ++j)
      for (std::size_t l = 1; l + 1 < ez.size(); ++l) {
        const V corner = V(ex[i], ey[j], ez[l]) + centre;
        // From the corner itself, in a random direction and along each axis (a ray along three block faces).
        expect_same(ours, reference, tris, {corner, random_unit(rng)}, tally);
        for (int a = 0; a < 3; ++a) {
          V d(0.0);
          d[a] = (rng() & 1) ? 1.0 : -1.0;
          expect_same(ours, reference, tris, {corner, d}, tally);
        }
        // Lying in the block face z = const, through the corner.
        const V in_face = glm::normalize(V(random_unit(rng).x, random_unit(rng).y, 0.0));
        expect_same(ours, reference, tris, {corner, in_face}, tally);
        // Aimed at the corner from outside the lattice, and from 10 km away.
        const V away = random_unit(rng);
        expect_same(ours, reference, tris, {corner + 20.0 * away, -away}, tally);
        expect_same(ours, reference, tris, {corner + 1e4 * away, -away}, tally);
      }
  EXPECT_GT(tally.checked, 200);
  // Interior block corners lie off the walls' quad edges: no ray there is ill-conditioned.
  EXPECT_EQ(tally.edge_cases, 0);
  std::printf("block corners: %d rays, %d edge cases\n", tally.checked, tally.edge_cases);
}

TEST(PlaneBlocks, WallsLyingExactlyOnBlockEdges) {
  // The same bounds and element count give the same blocks: move the inner walls onto inner block edges.
  const auto first = cube_lattice(4);
  const AxialCaster probe(first, kTestBlocks);
  const V centre = whole_metre_centre(first);
  const auto& e = probe.planes().blocks().edges(0);
  ASSERT_GE(e.size(), 6u);
  const std::vector<double> at{0.0, e[1] + centre.x, e[2] + centre.x, e[e.size() - 2] + centre.x, 4.0};
  const auto tris = cube_lattice(4, at);
  ASSERT_EQ(whole_metre_centre(tris), centre);
  const AxialCaster ours(tris, kTestBlocks);
  const BruteForceCaster reference(tris);
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 1; i < e.size() - 1; ++i)
      ASSERT_EQ(ours.planes().blocks().edges(k)[i], probe.planes().blocks().edges(k)[i]);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.01, 3.99);
  Tally tally;
  for (int i = 0; i < 3000; ++i) {
    const V o(u(rng), u(rng), u(rng));
    V d = random_unit(rng);
    if (i % 3 == 0) d = V(i % 2 ? 1.0 : -1.0, 0.0, 0.0);  // straight through the walls on the edges
    expect_same(ours, reference, tris, {o, d}, tally);
  }
  EXPECT_LE(tally.edge_cases, tally.checked / 1000);
}

TEST(PlaneBlocks, FlatModelHasOneLayerAndStillFindsEveryTile) {
  // One plane of tiles: the thin axis gets a single layer, the target spread over the other two.
  const auto tiles = testing::tiled_plane(40, 0.25, 3.0);
  const AxialCaster ours(tiles, kTestBlocks);
  const BruteForceCaster reference(tiles);
  const auto& tris = tiles;
  const PlaneBlocks& blocks = ours.planes().blocks();
  EXPECT_EQ(blocks.stats().blocks[2], 1u);
  EXPECT_GT(blocks.stats().blocks[0] * blocks.stats().blocks[1], 100u);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 11.0);
  Tally tally;
  for (int i = 0; i < 2000; ++i) {
    // Half of them start in the plane itself, leaving it by the self-hit policy.
    const V o(u(rng), u(rng), (i & 1) ? 5.0 : 3.0);
    const V d = random_unit(rng);
    expect_same(ours, reference, tris, {o, d, (i & 1) ? 0.0 : self_hit_tmin(d)}, tally);
  }
  // Straight down onto every block edge line.
  const V centre = whole_metre_centre(tiles);
  for (const double x : blocks.edges(0))
    for (const double y : blocks.edges(1))
      expect_same(ours, reference, tris, {V(x, y, 0.0) + V(centre.x, centre.y, 7.0), V(0, 0, -1)}, tally);
}

// A point of `t` to aim at: its vertex a (kind 0), a point on its edge a-b (kind 1), or a point inside.
V aim_point(const Triangle& t, int kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> w(0.0, 1.0);
  double a = w(rng), b = w(rng);
  if (kind == 0) a = b = 0.0;
  if (kind == 1) b = 0.0;
  if (a + b > 1.0) {
    a = 1.0 - a;
    b = 1.0 - b;
  }
  return t.a + a * (t.b - t.a) + b * (t.c - t.a);
}

// Small slanted triangles (BSP) scattered through an open box of axial tiles, one with a corner exactly on an
// interior block corner; `outside` adds one beyond the tiles' bounds, which the blocks cannot place.
std::vector<Triangle> box_with_slanted(const std::vector<double>& corner, bool outside) {
  auto tris = cube_lattice(4, {0.0, 4.0});
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> pos(0.5, 3.5);
  auto polygon = static_cast<std::uint32_t>(tris.size());
  for (int i = 0; i < 40; ++i) {
    const V p(pos(rng), pos(rng), pos(rng));
    tris.push_back({p, p + 0.3 * random_unit(rng), p + 0.3 * random_unit(rng), polygon++});
  }
  const V c(corner[0], corner[1], corner[2]);
  tris.push_back({c, c + V(0.3, 0.2, 0.1), c + V(-0.1, 0.3, 0.2), polygon++});
  if (outside) tris.push_back({V(6, 1, 1), V(6.5, 2, 1.5), V(6.2, 1.2, 2.5), polygon++});
  return tris;
}

TEST(PlaneBlocks, BspSearchOverTheMarkedBlocksFindsEveryHit) {
  // The first build gives the block edges; the same bounds and counts give the same blocks again.
  const V centre(2.0, 2.0, 2.0);
  const AxialCaster probe(box_with_slanted({2, 2, 2}, false), kTestBlocks);
  std::vector<double> corner(3);
  for (int k = 0; k < 3; ++k) {
    const auto& e = probe.planes().blocks().edges(k);
    ASSERT_GE(e.size(), 4u);
    corner[k] = e[e.size() / 2] + centre[k];
  }
  for (const bool outside : {false, true}) {
    const auto tris = box_with_slanted(corner, outside);
    const AxialCaster ours(tris, kTestBlocks);
    const BruteForceCaster reference(tris);
    // The one triangle's corner lies on a block corner (exactly without the outside triangle, which moves
    // the local frame's centre).
    const V shift = whole_metre_centre(tris) - centre;
    for (int k = 0; k < 3; ++k) {
      const auto& e = ours.planes().blocks().edges(k);
      const auto& f = probe.planes().blocks().edges(k);
      ASSERT_EQ(e.size(), f.size());
      for (std::size_t i = 0; i < e.size(); ++i) ASSERT_NEAR(e[i] + shift[k], f[i], 1e-12);
    }
    const auto& stats = ours.planes().blocks().stats();
    const std::size_t blocks = stats.blocks[0] * stats.blocks[1] * stats.blocks[2];
    // Inside the tiles' bounds the slanted triangles mark some blocks, not all: rays skip the BSP elsewhere.
    if (!outside) {
      EXPECT_GT(stats.marked, 0u);
      EXPECT_LT(stats.marked, blocks);
    }
    std::mt19937_64 rng(outside ? 31 : 30);
    std::uniform_real_distribution<double> pos(0.05, 3.95);
    Tally tally;
    const std::size_t first_slanted = 6 * 8 * 8 * 2;
    for (std::size_t i = first_slanted; i < tris.size(); ++i) {
      const Triangle& t = tris[i];
      for (int j = 0; j < 40; ++j) {
        // Vertices, points on edges and inside, from anywhere in the box (and from beyond the outside one).
        const V target = aim_point(t, j % 4, rng);
        const V o = t.a.x > 5.0 ? V(8.0, pos(rng), pos(rng)) : V(pos(rng), pos(rng), pos(rng));
        expect_same(ours, reference, tris, {o, target - o}, tally);
        // Segments ending just short of the target and just past it (occlusion rays).
        expect_same(ours, reference, tris, {o, target - o, 0.0, 0.999}, tally);
        expect_same(ours, reference, tris, {o, target - o, 0.0, 1.001}, tally);
      }
    }
    for (int i = 0; i < 5000; ++i)
      expect_same(ours, reference, tris, {V(pos(rng), pos(rng), pos(rng)), random_unit(rng)}, tally);
    EXPECT_LE(tally.edge_cases, tally.checked / 100);
    std::printf("slanted in blocks (outside %d): %zu of %zu blocks marked, %d rays, %d edge cases\n", outside,
                stats.marked, blocks, tally.checked, tally.edge_cases);
  }
}

// Slanted triangles that reach a block only on its face: one with an edge lying in a block face, one with
// only a vertex on a block edge line, one just beyond a face by less than the margin. The part of each inside
// the neighbouring block is a segment, a point or nothing, so that block's marked box is flat or absent; rays
// from that block aimed at the edge and the vertex must still find them.
TEST(PlaneBlocks, MarkedBoxesOfTrianglesTouchingABlockFace) {
  const auto tiles = cube_lattice(4, {0.0, 4.0});
  const AxialCaster probe(tiles, kTestBlocks);
  const auto& ex = probe.planes().blocks().edges(0);
  const auto& ey = probe.planes().blocks().edges(1);
  const auto& ez = probe.planes().blocks().edges(2);
  ASSERT_GE(ex.size(), 4u);
  const V centre = whole_metre_centre(tiles);
  const double x = ex[ex.size() / 2] + centre.x, y = ey[ey.size() / 2] + centre.y;
  const double z = ez[ez.size() / 2] + centre.z;
  auto tris = tiles;
  auto polygon = static_cast<std::uint32_t>(tris.size());
  const std::size_t first_slanted = tris.size();
  tris.push_back({V(x, y - 0.3, z - 0.2), V(x, y + 0.2, z + 0.3), V(x + 0.4, y, z + 0.1), polygon++});
  tris.push_back({V(x, y, z + 0.1), V(x + 0.3, y + 0.1, z + 0.3), V(x + 0.1, y + 0.4, z + 0.2), polygon++});
  tris.push_back({V(x + 1e-12, y - 0.9, z + 0.5), V(x + 0.3, y - 0.6, z + 0.6), V(x + 0.2, y - 0.8, z + 0.9),
                  polygon++});
  const AxialCaster ours(tris, kTestBlocks);
  for (int k = 0; k < 3; ++k)  // the same bounds and counts: the same blocks
    ASSERT_EQ(ours.planes().blocks().edges(k).size(), probe.planes().blocks().edges(k).size());
  const BruteForceCaster reference(tris);
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> off(0.05, 0.6);
  Tally tally;
  for (std::size_t i = first_slanted; i < tris.size(); ++i) {
    const Triangle& t = tris[i];
    for (int j = 0; j < 300; ++j) {
      // The vertex a, points on the edge a-b and inside, from the side x < x_edge (the neighbouring block).
      const V target = aim_point(t, j % 3, rng);
      const V o = target - V(off(rng), off(rng) - 0.3, off(rng) - 0.3);
      expect_same(ours, reference, tris, {o, target - o}, tally);
      expect_same(ours, reference, tris, {o, target - o, 0.0, 1.001}, tally);
    }
  }
  EXPECT_LE(tally.edge_cases, tally.checked / 100);
  std::printf("triangles touching block faces: %zu blocks marked, %d rays, %d edge cases\n",
              ours.planes().blocks().stats().marked, tally.checked, tally.edge_cases);
}

TEST(PlaneBlocks, EmptyAndSingleTriangleModels) {
  const AxialCaster none(std::vector<Triangle>{});
  EXPECT_FALSE(none.closest({V(0, 0, 0), V(1, 0, 0)}).hit());
  EXPECT_FALSE(none.occluded({V(0, 0, 0), V(1, 0, 0)}));
  // A single triangle: the grid is one block, thin on the triangle's axis.
  const AxialCaster one(std::vector<Triangle>{{V(0, 0, 1), V(2, 0, 1), V(0, 2, 1), 7}});
  const auto h = one.closest({V(0.5, 0.5, 0), V(0, 0, 1)});
  ASSERT_TRUE(h.hit());
  EXPECT_EQ(h.polygon, 7u);
  EXPECT_DOUBLE_EQ(h.t, 1.0);
  // Starting exactly in its plane, or past it, nothing.
  EXPECT_FALSE(one.closest({V(0.5, 0.5, 1), V(0, 0, 1)}).hit());
  EXPECT_FALSE(one.closest({V(0.5, 0.5, 1.5), V(0, 0, 1)}).hit());
  // A ray in the plane, parallel to it: zero-area intersection, no hit (the shared convention).
  EXPECT_FALSE(one.closest({V(-1, 0.5, 1), V(1, 0, 0)}).hit());
}

}  // namespace test_plane_blocks
}  // namespace walk::compiler
