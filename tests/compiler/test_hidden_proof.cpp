// The hidden-polygon proof and its parts: a cover's containment test, fused occluder planes at their
// degenerate contacts, and proofs through a corner where two walls meet, checked against random sight lines.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>
#include <random>

#include "compiler/visibility/cover_index.hpp"
#include "compiler/visibility/hidden_proof.hpp"
#include "compiler/visibility/occluder_planes.hpp"
#include "compiler/visibility/trace_through_glass.hpp"
#include "test_visibility_util.hpp"

namespace walk::compiler {
namespace test_hidden_proof {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
using testing::MiniBuilding;

ClipperLib::Path square(ClipperLib::cInt x0, ClipperLib::cInt y0, ClipperLib::cInt x1, ClipperLib::cInt y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// A 10 x 10 cover (units) with a 2 x 2 hole in the middle, as a union hands it over.
CoverIndex holed_square() {
  ClipperLib::Path hole = square(4, 4, 6, 6);
  ClipperLib::ReversePath(hole);
  return CoverIndex({square(0, 0, 10, 10), hole});
}

TEST(CoverIndex, ContainsOnlySectionsWhollyInside) {
  const CoverIndex c = holed_square();
  EXPECT_TRUE(c.contains(square(1, 1, 3, 3), 0.0));
  EXPECT_TRUE(c.contains(square(0, 0, 10, 3), 0.0)) << "touching the outline from inside";
  EXPECT_FALSE(c.contains(square(3, 3, 5, 5), 0.0)) << "over the hole's edge";
  EXPECT_FALSE(c.contains(square(4, 4, 6, 6), 0.0)) << "the hole itself";
  EXPECT_FALSE(c.contains(square(11, 1, 12, 2), 0.0)) << "outside";
  EXPECT_FALSE(c.contains(square(9, 1, 11, 2), 0.0)) << "across the outline";
  EXPECT_FALSE(c.contains(square(1, 1, 9, 9), 0.0)) << "round the hole: its outline lies inside";
  // The inset forgives what lies within it of the section's edges, and a section thinner than twice it.
  EXPECT_TRUE(c.contains(square(-1, 0, 4, 5), 1.5)) << "poking 1 unit past the outline";
  EXPECT_FALSE(c.contains(square(-3, 0, 3, 5), 1.5)) << "poking 3 units past it";
  EXPECT_TRUE(c.contains(square(20, 1, 22, 3), 1.5)) << "2 wide, inset 1.5 a side: nothing left";
  EXPECT_FALSE(CoverIndex().contains(square(1, 1, 2, 2), 0.0)) << "an empty cover covers nothing";
}

TEST(CoverIndex, PathsNearAreThoseWhoseBoundsMeetTheBox) {
  const CoverIndex c({square(0, 0, 10, 10), square(20, 0, 30, 10)});
  ClipperLib::Paths near;
  c.paths_near({11, 0}, {19, 5}, near);
  EXPECT_TRUE(near.empty());
  c.paths_near({9, 0}, {21, 5}, near);
  EXPECT_EQ(near.size(), 2u);
}

// A wall in the plane x = 0 facing +x, built from the given (y0, y1) pieces, z 0..2.
std::vector<VisPolygon> wall_pieces(std::initializer_list<std::pair<double, double>> pieces) {
  MiniBuilding m;
  for (const auto& [y0, y1] : pieces) m.rect(0, 0.0, y0, y1, 0.0, 2.0);
  return vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
}

Winding corners(const Box& b) {
  Winding w;
  for (int c = 0; c < 8; ++c)
    w.push_back({c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z});
  return w;
}

// A target quad in the plane x = `x`, over y0..y1 and z0..z1.
Winding quad_at(double x, double y0, double y1, double z0, double z1) {
  return {{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}};
}

TEST(OccluderPlanes, PiecesOfOneWallBlockTogether) {
  const Box viewer{{1.0, 0.5, 0.5}, {2.0, 1.5, 1.5}};
  const Winding target = quad_at(-1.0, 0.6, 1.4, 0.6, 1.4);
  const auto both = wall_pieces({{0.0, 1.0}, {1.0, 2.0}});
  const OccluderPlanes planes(both, true);
  ASSERT_EQ(planes.size(), 1u) << "one plane for both pieces";
  EXPECT_TRUE(planes.blocks(0, corners(viewer), target));
  for (const auto& piece : {std::pair{0.0, 1.0}, std::pair{1.0, 2.0}}) {
    const OccluderPlanes one(wall_pieces({piece}), true);
    EXPECT_FALSE(one.blocks(0, corners(viewer), target)) << "one piece alone leaves the other half open";
  }
}

TEST(OccluderPlanes, DegenerateContacts) {
  const OccluderPlanes planes(wall_pieces({{0.0, 2.0}}), true);
  const Box viewer{{1.0, 0.5, 0.5}, {2.0, 1.5, 1.5}};
  // The target lying in the wall's plane is never hidden by it.
  EXPECT_FALSE(planes.blocks(0, corners(viewer), quad_at(0.0, 0.6, 1.4, 0.6, 1.4)));
  // A viewer straddling the plane.
  EXPECT_FALSE(
      planes.blocks(0, corners({{-0.5, 0.5, 0.5}, {2.0, 1.5, 1.5}}), quad_at(-1.0, 0.6, 1.4, 0.6, 1.4)));
  // A target touching the plane along an edge (a floor meeting the wall's foot), the rest behind: hidden.
  const Winding floor_behind{{0.0, 0.5, 0.0}, {-1.0, 0.5, 0.0}, {-1.0, 1.5, 0.0}, {0.0, 1.5, 0.0}};
  EXPECT_TRUE(planes.blocks(0, corners(viewer), floor_behind));
  // A source touching the plane (a portal ending where the wall begins), the rest in front: its sight
  // lines cross the wall at or beyond that edge.
  const Winding portal{{0.0, 0.5, 0.5}, {1.0, 0.5, 0.5}, {1.0, 0.5, 1.5}, {0.0, 0.5, 1.5}};
  EXPECT_TRUE(planes.blocks(0, portal, quad_at(-1.0, 0.6, 1.4, 0.6, 1.4)));
  // A target reaching past the wall's top.
  EXPECT_FALSE(planes.blocks(0, corners(viewer), quad_at(-1.0, 0.6, 1.4, 0.6, 3.0)));
}

TEST(OccluderPlanes, BackFacesBlockOnlyWhenDrawnFromBothSides) {
  const auto wall = wall_pieces({{0.0, 2.0}});
  const Box behind{{-2.0, 0.5, 0.5}, {-1.0, 1.5, 1.5}};
  const Winding target = quad_at(1.0, 0.6, 1.4, 0.6, 1.4);
  EXPECT_FALSE(OccluderPlanes(wall, true).blocks(0, corners(behind), target)) << "seen from its back, culled";
  EXPECT_TRUE(OccluderPlanes(wall, false).blocks(0, corners(behind), target)) << "drawn both sides";
}

TEST(OccluderPlanes, FloatCracksCloseButAMillimetreGapLeaks) {
  const Box viewer{{1.0, 0.5, 0.5}, {2.0, 1.5, 1.5}};
  const Winding target = quad_at(-1.0, 0.6, 1.4, 0.6, 1.4);
  const OccluderPlanes cracked(wall_pieces({{0.0, 1.0}, {1.0 + 2e-6, 2.0}}), true);
  EXPECT_TRUE(cracked.blocks(0, corners(viewer), target)) << "a 2 um crack is rounding";
  const OccluderPlanes gap(wall_pieces({{0.0, 1.0}, {1.001, 2.0}}), true);
  const Shaft s = gap.shaft(0, corners(viewer), target, true);
  EXPECT_TRUE(s.applies);
  EXPECT_FALSE(s.blocked) << "sight passes a 1 mm slit";
  ASSERT_EQ(s.leaks.size(), 1u);
  // The section spans z 0.55..1.45 where the 1 mm slit crosses it.
  EXPECT_NEAR(s.leak_area, 0.001 * 0.9, 1e-4) << "the slit's part of the section";
  for (const auto& p : s.leaks.front()) {
    EXPECT_NEAR(p.x, 0.0, 1e-12) << "windows lie in the plane";
    EXPECT_GT(p.y, 1.0 - 1e-5);
    EXPECT_LT(p.y, 1.001 + 1e-5);
  }
}

// A brute-force caster over the polygons' triangles, each carrying its polygon's index.
std::unique_ptr<RayCaster> brute_caster(const std::vector<VisPolygon>& polygons) {
  std::vector<Triangle> triangles;
  for (std::uint32_t p = 0; p < polygons.size(); ++p)
    for (const auto& t : polygons[p].triangles) triangles.push_back({t[0], t[1], t[2], p});
  return make_ray_caster("brute", triangles);
}

// Of `n` random sight lines from a point of `viewer` to a point `target_point(u)` draws (u(): uniform in
// 0..1, drawn after the viewer point), how many meet `target` first.
template <typename TargetPoint>
int lines_reaching(const std::vector<VisPolygon>& polygons, const RayCaster& caster, const Box& viewer,
                   std::uint32_t target, int n, std::uint64_t seed, TargetPoint target_point) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  auto u = [&] { return uniform(rng); };
  std::vector<char> glass(polygons.size(), 0);
  int reach = 0;
  for (int i = 0; i < n; ++i) {
    Ray r;
    r.origin = viewer.min + Vec3{u(), u(), u()} * viewer.size();
    r.dir = target_point(u) - r.origin;
    std::vector<std::uint32_t> ids;
    trace_through_glass(caster, r, glass, ids, true);
    reach += !ids.empty() && ids.front() == target ? 1 : 0;
  }
  return reach;
}

// Two walls meeting at a corner (top view: one along x = 0 for y >= 0 facing +x, one along y = 0 for
// x <= 0 facing -y, both z 0..3), a viewer box in the quadrant x > 0, y < 0 and a target in the quadrant
// x < 0, y > 0. Every sight line between them crosses one wall or the other, but sight lines through the
// corner cross both planes right at their meeting edge: no split of the pair ever puts all of a piece's
// sight lines through one wall. `gap`: the wall along x = 0 starts that far from the corner.
struct Corner {
  std::vector<VisPolygon> polygons;
  std::unique_ptr<RayCaster> caster;
  std::uint32_t target;
  Box viewer{{0.5, -1.5, 0.5}, {1.5, -0.5, 1.5}};
};

Corner corner(double gap) {
  MiniBuilding m;
  m.rect(0, 0.0, gap, 3.0, 0.0, 3.0, model::Role::Opaque, 1);    // x = 0, y gap..3, facing +x
  m.rect(1, 0.0, 0.0, 3.0, -3.0, 0.0, model::Role::Opaque, -1);  // y = 0, x -3..0 (v), facing -y
  Corner c;
  c.target = m.rect(0, -1.0, 0.5, 1.5, 0.5, 1.5, model::Role::Opaque, 1);  // facing the corner
  c.polygons = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  c.caster = brute_caster(c.polygons);
  return c;
}

// Of `n` random sight lines from the corner's viewer box to its target, how many reach it.
int sight_lines_reaching(const Corner& c, int n) {
  return lines_reaching(c.polygons, *c.caster, c.viewer, c.target, n, 5, [](auto& u) {
    return Vec3{-1.0, 0.5 + u(), 0.5 + u()};
  });
}

TEST(HiddenProver, ThroughACornerWhereTwoWallsMeet) {
  const Corner c = corner(0.0);
  ASSERT_EQ(sight_lines_reaching(c, 20000), 0) << "the corner is closed";
  const HiddenProver prover(c.polygons, *c.caster, true);
  ProofOptions o;
  o.max_pairs = 4096;
  ProofStats stats;
  EXPECT_EQ(prover.prove_from_box(c.viewer, c.target, o, &stats), Verdict::Hidden);
  EXPECT_GT(stats.windows, 0u) << "it went through a window past one wall's end";
  // Splitting alone never settles the sight lines through the corner itself.
  o.window_fraction = 0.0;
  EXPECT_EQ(prover.prove_from_box(c.viewer, c.target, o), Verdict::Undecided);
  // Nor does a budget too small for the proof: the polygon is then kept.
  o.window_fraction = ProofOptions{}.window_fraction;
  o.max_pairs = 1;
  EXPECT_EQ(prover.prove_from_box(c.viewer, c.target, o), Verdict::Undecided);
}

TEST(HiddenProver, AGapAtTheCornerIsNeverProvenClosed) {
  for (const double gap : {0.02, 1e-3}) {
    const Corner c = corner(gap);
    EXPECT_GT(sight_lines_reaching(c, 200000), 0) << "sight passes the " << gap << " m gap";
    const HiddenProver prover(c.polygons, *c.caster, true);
    ProofOptions o;
    o.max_pairs = 4096;
    EXPECT_NE(prover.prove_from_box(c.viewer, c.target, o), Verdict::Hidden) << gap;
  }
}

TEST(HiddenProver, ATargetFacingAwayOrSeenIsSettledAtOnce) {
  const Corner c = corner(0.0);
  const HiddenProver prover(c.polygons, *c.caster, true);
  // The wall along x = 0 seen from the viewer: visible at the first sight line.
  ProofStats stats;
  EXPECT_EQ(prover.prove_from_box(c.viewer, 0, ProofOptions{}, &stats), Verdict::Visible);
  EXPECT_EQ(stats.pairs, 1u);
  // The target faces +x: from a viewer beyond it (x < -1) it is turned away, hidden without a sight line.
  const Box far_side{{-2.5, 0.5, 0.5}, {-1.5, 1.5, 1.5}};
  EXPECT_EQ(prover.prove_from_box(far_side, c.target, ProofOptions{}), Verdict::Hidden);
}

// The corner's walls with a detail cluster (a small closed box, one item) at `lo`..`hi` in place of the
// target polygon: proven hidden face by face of its box.
Corner corner_with_cluster(double gap, Vec3 lo, Vec3 hi) {
  MiniBuilding m;
  m.rect(0, 0.0, gap, 3.0, 0.0, 3.0, model::Role::Opaque, 1);
  m.rect(1, 0.0, 0.0, 3.0, -3.0, 0.0, model::Role::Opaque, -1);
  Corner c;
  c.polygons = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  MiniBuilding box;
  box.room(lo, hi);
  VisPolygon cluster;
  cluster.detail = true;
  cluster.box = {lo, hi};
  for (const auto& p : vis_polygons(box.b.vertices, box.b.indices, box.b.polygons))
    cluster.triangles.insert(cluster.triangles.end(), p.triangles.begin(), p.triangles.end());
  c.target = static_cast<std::uint32_t>(c.polygons.size());
  c.polygons.push_back(std::move(cluster));
  c.caster = brute_caster(c.polygons);
  return c;
}

TEST(HiddenProver, ADetailClusterIsProvenHiddenByItsBoxFaces) {
  ProofOptions o;
  o.max_pairs = 4096;
  const Vec3 lo{-1.5, 0.5, 0.5}, hi{-1.0, 1.5, 1.5};  // behind the corner
  {
    const Corner c = corner_with_cluster(0.0, lo, hi);
    const HiddenProver prover(c.polygons, *c.caster, true);
    EXPECT_EQ(prover.prove_from_box(c.viewer, c.target, o), Verdict::Hidden);
    // Seen from beside it, not round the corner.
    const Box beside{{-1.0, 2.0, 0.5}, {0.0, 3.0, 1.5}};
    EXPECT_EQ(prover.prove_from_box(beside, c.target, o), Verdict::Visible);
  }
  // A 2 cm gap where the walls meet: some sight line passes, so never hidden.
  const Corner gap = corner_with_cluster(0.02, lo, hi);
  const HiddenProver prover(gap.polygons, *gap.caster, true);
  EXPECT_NE(prover.prove_from_box(gap.viewer, gap.target, o), Verdict::Hidden);
  // In the viewer's own quadrant, in plain sight: seen at once.
  const Corner open = corner_with_cluster(0.0, {2.0, -1.5, 0.5}, {2.5, -0.5, 1.5});
  const HiddenProver open_prover(open.polygons, *open.caster, true);
  ProofStats stats;
  EXPECT_EQ(open_prover.prove_from_box(open.viewer, open.target, o, &stats), Verdict::Visible);
  EXPECT_LE(stats.pairs, 2u);
}

// Stopping once the pieces still waiting cannot fit the allowance never loses a hidden verdict: at every
// allowance the proof with the early stop ends hidden exactly when the one run to its allowance does, and
// never takes more pairs; an undecided one takes fewer. Through the corner (windows and splits), a
// cluster's box faces (several outlines from one viewer) and splits alone (no windows).
TEST(HiddenProver, StoppingEarlyNeverLosesAHiddenVerdict) {
  const Corner walls = corner(0.0);
  const Corner cluster = corner_with_cluster(0.0, {-1.5, 0.5, 0.5}, {-1.0, 1.5, 1.5});
  int fewer = 0, hidden = 0;
  for (const Corner* c : {&walls, &cluster}) {
    const HiddenProver prover(c->polygons, *c->caster, true);
    for (const double window_fraction : {0.5, 0.0})
      for (int pairs = 1; pairs <= 300; ++pairs) {  // every allowance, the edge where hidden begins too
        ProofOptions o;
        o.max_pairs = pairs;
        o.window_fraction = window_fraction;
        ProofStats early, full;
        const Verdict e = prover.prove_from_box(c->viewer, c->target, o, &early);
        o.stop_early = false;
        const Verdict f = prover.prove_from_box(c->viewer, c->target, o, &full);
        ASSERT_EQ(e == Verdict::Hidden, f == Verdict::Hidden)
            << pairs << " pairs, windows " << window_fraction;
        EXPECT_LE(early.pairs, full.pairs) << pairs;
        fewer += early.pairs < full.pairs;
        hidden += e == Verdict::Hidden;
      }
  }
  EXPECT_GT(hidden, 100) << "the allowances reach the hidden verdicts";
  EXPECT_GT(fewer, 100) << "the early stop spares pairs";
}

// Two floors with a hole each, offset (side view: x across, z up; every polygon faces up, y -20..20):
// floor A in z = 0 open over x -4..4, floor B in z = -3 open over x 5.5..7. A small viewer high over hole A
// and a target in z = -6 under both, x 4..9: some sight lines pass hole A and some would pass hole B, but
// those through hole A land on floor B short of its hole (x <= 5.23), and every other one lands on floor
// A. Through hole A (a window on floor A) the target is seen from the hole's edge through hole B: only
// the part the viewer's lines reach (x <= 6.5) is hidden behind floor B.
struct TwoHoles {
  std::vector<VisPolygon> polygons;
  std::unique_ptr<RayCaster> caster;
  std::uint32_t target;
  Box viewer{{-0.1, -0.1, 10.0}, {0.1, 0.1, 10.2}};
};

// `hole_b`: where floor B's hole starts.
TwoHoles two_holes(double hole_b) {
  MiniBuilding m;
  m.rect(2, 0.0, -20.0, -4.0, -20.0, 20.0);
  m.rect(2, 0.0, 4.0, 20.0, -20.0, 20.0);
  m.rect(2, -3.0, -20.0, hole_b, -20.0, 20.0);
  m.rect(2, -3.0, 7.0, 20.0, -20.0, 20.0);
  TwoHoles h;
  h.target = m.rect(2, -6.0, 4.0, 9.0, -0.1, 0.1);
  h.polygons = vis_polygons(m.b.vertices, m.b.indices, m.b.polygons);
  h.caster = brute_caster(h.polygons);
  return h;
}

// Of `n` random sight lines from the viewer to the target, how many reach it.
int sight_lines_reaching(const TwoHoles& h, int n) {
  return lines_reaching(h.polygons, *h.caster, h.viewer, h.target, n, 3, [](auto& u) {
    return Vec3{4.0 + 5.0 * u(), -0.1 + 0.2 * u(), -6.0};
  });
}

TEST(HiddenProver, ThroughAHoleOnlyWhatTheViewerReachesCounts) {
  ProofOptions o;
  o.max_pairs = 64;
  {
    const TwoHoles h = two_holes(5.5);
    ASSERT_EQ(sight_lines_reaching(h, 200000), 0) << "the target is hidden";
    const HiddenProver prover(h.polygons, *h.caster, true);
    ProofStats stats;
    EXPECT_EQ(prover.prove_from_box(h.viewer, h.target, o, &stats), Verdict::Hidden);
    EXPECT_GT(stats.windows, 0u) << "through hole A as a window";
    // Before the window's far side was cut to the viewer's reach, it stayed undecided at 64 pairs (63 of
    // them windows); now a few settle it.
    EXPECT_LE(stats.pairs, 8u);
  }
  // Floor B's hole from x = 5.0 meets the lines through hole A (they land at x <= 5.23): seen.
  const TwoHoles h = two_holes(5.0);
  ASSERT_GT(sight_lines_reaching(h, 200000), 0);
  const HiddenProver prover(h.polygons, *h.caster, true);
  o.max_pairs = 4096;
  EXPECT_NE(prover.prove_from_box(h.viewer, h.target, o), Verdict::Hidden);
}

TEST(ProofAllowance, FollowsTheTrianglesBetweenTheFloorAndTheCap) {
  EXPECT_EQ(proof_allowance(100, 50.0, false, 256, 32), 256) << "larger than the cell's mean item";
  EXPECT_EQ(proof_allowance(50, 50.0, false, 256, 32), 256) << "the mean item";
  EXPECT_EQ(proof_allowance(25, 50.0, false, 256, 32), 128) << "half the mean";
  EXPECT_EQ(proof_allowance(1, 50.0, false, 256, 32), 32) << "never under the floor";
  EXPECT_EQ(proof_allowance(1000, 50.0, true, 256, 32), 32) << "a cluster, whatever its triangles";
}

TEST(ProofAllowance, DegenerateInputs) {
  EXPECT_EQ(proof_allowance(0, 50.0, false, 256, 32), 32) << "no triangles";
  EXPECT_EQ(proof_allowance(10, 0.0, false, 256, 32), 256) << "no mean known";
  EXPECT_EQ(proof_allowance(10, -1.0, false, 256, 32), 256);
  EXPECT_EQ(proof_allowance(10, std::nan(""), false, 256, 32), 256);
  EXPECT_EQ(proof_allowance(10, 50.0, false, 16, 32), 16) << "a floor above the cap is the cap";
  EXPECT_EQ(proof_allowance(10, 50.0, true, 16, 32), 16);
  EXPECT_EQ(proof_allowance(10, 50.0, false, 0, 32), 0) << "no proofs";
  EXPECT_EQ(proof_allowance(10, 50.0, true, 0, 32), 0);
  EXPECT_EQ(proof_allowance(10, 50.0, false, -5, 32), 0) << "never negative";
  EXPECT_EQ(proof_allowance(10, 50.0, false, 256, -3), 51) << "a negative floor is none";
}

}  // namespace test_hidden_proof
}  // namespace walk::compiler
