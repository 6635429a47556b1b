// Degenerate cases of the geometric predicates under the visibility stages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/partition/axial_cover.hpp"
#include "compiler/partition/partition.hpp"
#include "compiler/visibility/vis_items.hpp"

namespace walk::compiler {
namespace test_visibility_predicates {  // named, not anonymous: the suite compiles as unity batches

const Winding kSquare{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

double area(const Winding& w) {
  model::Vec3 n{0.0};
  for (std::size_t i = 1; i + 1 < w.size(); ++i) n += glm::cross(w[i] - w[0], w[i + 1] - w[0]);
  return 0.5 * glm::length(n);
}

TEST(VisibilityPredicates, ClipKeepsAllWhenInFrontOrOnPlane) {
  EXPECT_EQ(clip_front(kSquare, {{1, 0, 0}, 1.0}).size(), 4u);  // x >= -1: all in front
  EXPECT_EQ(clip_front(kSquare, {{0, 0, 1}, 0.0}).size(), 4u);  // the winding lies in the plane: kept
}

// A portal's plane is axial: its normal has no other component (a default Plane's +z once leaked into x and y
// portals and turned DM1's flow planes, missing 0.2% of pixels).
TEST(VisibilityPredicates, AxialPlaneIsExactlyAxial) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0, 0.0}) {
      const Plane p = axial_plane(axis, 2.5, sign);
      model::Vec3 expected{0.0};
      expected[axis] = sign > 0.0 ? 1.0 : -1.0;  // zero counts as negative: a side is always chosen
      EXPECT_EQ(p.n, expected) << axis << " " << sign;
      model::Vec3 on{7.0, -3.0, 11.0};
      on[axis] = 2.5;
      EXPECT_EQ(p.distance(on), 0.0);
      on[axis] = 3.5;
      EXPECT_DOUBLE_EQ(p.distance(on), expected[axis]);
    }
  }
}

TEST(VisibilityPredicates, ClipDropsAllBehind) {
  EXPECT_TRUE(clip_front(kSquare, {{1, 0, 0}, -2.0}).empty());  // x >= 2
  EXPECT_TRUE(clip_front({}, {{1, 0, 0}, 0.0}).empty());
}

TEST(VisibilityPredicates, ClipTouchingEdgeKeepsTheContact) {
  const Winding w = clip_front(kSquare, {{1, 0, 0}, -1.0});  // x >= 1: only the edge x = 1 touches
  ASSERT_EQ(w.size(), 2u);
  for (const auto& p : w) EXPECT_DOUBLE_EQ(p.x, 1.0);
  const Winding corner = clip_front(kSquare, {glm::normalize(model::Vec3{1, 1, 0}), -std::sqrt(2.0)});
  ASSERT_EQ(corner.size(), 1u);  // only the corner (1,1) touches
  EXPECT_EQ(corner[0], (model::Vec3{1, 1, 0}));
}

TEST(VisibilityPredicates, ClipCrossingHalvesTheArea) {
  const Winding w = clip_front(kSquare, {{1, 0, 0}, -0.5});
  EXPECT_NEAR(area(w), 0.5, 1e-12);
  const Winding diag = clip_front(kSquare, {glm::normalize(model::Vec3{1, 1, 0}), -std::sqrt(0.5)});
  EXPECT_NEAR(area(diag), 0.5, 1e-12);  // through two opposite corners
}

TEST(VisibilityPredicates, WindingWidthOfDegenerateAndThinWindings) {
  EXPECT_EQ(winding_width({}), 0.0);
  EXPECT_EQ(winding_width({{0, 0, 0}, {1, 0, 0}}), 0.0);             // a segment
  EXPECT_EQ(winding_width({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), 0.0);  // collinear
  EXPECT_EQ(winding_width({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}), 0.0);  // one point, repeated
  EXPECT_NEAR(winding_width(kSquare), 1.0, 1e-12);
  // A 2 m x 1e-5 m strip (what clipping leaves along a plane) and a triangle of height 0.5 over a 1 m base
  // (its other two sides are 0.71 m from the opposite corner).
  EXPECT_NEAR(winding_width({{0, 0, 0}, {2, 0, 0}, {2, 1e-5, 0}, {0, 1e-5, 0}}), 1e-5, 1e-12);
  EXPECT_NEAR(winding_width({{0, 0, 5}, {1, 0, 5}, {0.5, 0.5, 5}}), 0.5, 1e-12);
  // A repeated vertex does not make a zero-length edge count.
  EXPECT_NEAR(winding_width({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}), 1.0, 1e-12);
}

TEST(VisibilityPredicates, HullOfDegeneratePointSets) {
  EXPECT_TRUE(convex_hull({}, {0, 0, 1}).empty());
  EXPECT_EQ(convex_hull({{1, 2, 3}}, {0, 0, 1}).size(), 1u);
  EXPECT_EQ(convex_hull({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, {0, 0, 1}).size(), 1u);
  EXPECT_EQ(convex_hull({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {0, 0, 1}).size(), 2u);  // collinear
  EXPECT_EQ(
      convex_hull({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}, {1, 0, 0}}, {0, 0, 1}).size(),
      4u);  // interior and repeated points dropped
  EXPECT_NEAR(area(convex_hull({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 0, 1})), 1.0, 1e-12);
}

TEST(VisibilityPredicates, SeparatorsBetweenFacingPortals) {
  // Two unit squares facing each other 1 m apart: the separators bound the sight lines between them.
  const Winding a = kSquare;
  const Winding b{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<Plane> seps;
  separating_planes(a, b, false, seps);
  ASSERT_FALSE(seps.empty());
  for (const auto& p : seps) {
    for (const auto& q : a) EXPECT_LE(p.distance(q), 1e-9);
    for (const auto& q : b) EXPECT_GE(p.distance(q), -1e-9);
  }
  // A point beyond b along a sight line survives; one far off to the side does not.
  const model::Vec3 on_line{0.5, 0.5, 3.0}, off{10.0, 0.5, 2.0};
  bool off_cut = false;
  for (const auto& p : seps) {
    EXPECT_GE(p.distance(on_line), -1e-9);
    off_cut |= p.distance(off) < 0.0;
  }
  EXPECT_TRUE(off_cut);
}

TEST(VisibilityPredicates, SeparatorsOfCoplanarOrDegeneratePortalsAreNone) {
  std::vector<Plane> seps;
  separating_planes(kSquare, Winding{{2, 0, 0}, {3, 0, 0}, {3, 1, 0}}, false, seps);  // same plane
  EXPECT_TRUE(seps.empty());
  separating_planes(Winding{{0, 0, 0}}, kSquare, false, seps);  // a point has no edges
  EXPECT_TRUE(seps.empty());
  separating_planes(kSquare, Winding{}, false, seps);
  EXPECT_TRUE(seps.empty());
}

// A pass corner just behind a separator: within kPlaneEpsilon (metres, whatever the portals' size, since the
// candidates are judged unnormalised) it counts as on the plane and the plane separates; past it, not.
TEST(VisibilityPredicates, SeparatorToleranceIsInMetresAtAnyScale) {
  for (const double scale : {1.0, 1000.0}) {
    for (const double behind : {0.5 * kPlaneEpsilon, 4.0 * kPlaneEpsilon}) {
      const Winding source{{0, 0, 0}, {scale, 0, 0}, {scale, scale, 0}, {0, scale, 0}};
      // The plane through the source's edge x = scale and the pass corner (0, 0, scale) is x + z = scale;
      // the corner (0, scale, scale) is moved `behind` metres behind it.
      const double dz = behind * std::sqrt(2.0);
      const Winding pass{{0, 0, scale}, {scale, 0, scale}, {scale, scale, scale}, {0, scale, scale - dz}};
      std::vector<Plane> seps;
      separating_planes(source, pass, false, seps);
      const bool found = std::any_of(seps.begin(), seps.end(), [&](const Plane& p) {
        return std::abs(p.distance({scale, 0, 0})) < 1e-9 * scale &&
               std::abs(p.distance({scale, scale, 0})) < 1e-9 * scale &&
               std::abs(p.distance({0, 0, scale})) < 1e-9 * scale;
      });
      EXPECT_EQ(found, behind < kPlaneEpsilon) << "scale " << scale << ", behind " << behind;
      for (const auto& p : seps) EXPECT_NEAR(glm::length(p.n), 1.0, 1e-12);
    }
  }
}

TEST(VisibilityPredicates, FacesAwayFromABox) {
  // A unit square in z = 1 facing +z (counter-clockwise seen from above).
  VisPolygon up;
  up.triangles = {{model::Vec3{0, 0, 1}, model::Vec3{1, 0, 1}, model::Vec3{1, 1, 1}},
                  {model::Vec3{0, 0, 1}, model::Vec3{1, 1, 1}, model::Vec3{0, 1, 1}}};
  EXPECT_TRUE(faces_away_from(up, Box{{0, 0, -2}, {3, 3, 0}}));    // wholly below
  EXPECT_TRUE(faces_away_from(up, Box{{0, 0, 0}, {3, 3, 1}}));     // touching its plane from below: edge-on
  EXPECT_FALSE(faces_away_from(up, Box{{0, 0, 0}, {3, 3, 1.5}}));  // reaching above it
  EXPECT_FALSE(faces_away_from(up, Box{{0, 0, 2}, {1, 1, 3}}));    // wholly above
  EXPECT_FALSE(
      faces_away_from(up, Box{{5, 5, 0.999}, {6, 6, 1.001}}));  // straddling its plane off to the side
  // A bent polygon faces away only if every triangle does: tilt one up past the box's top.
  VisPolygon bent = up;
  bent.triangles[1][2] = {0, 1, 3};
  EXPECT_TRUE(faces_away_from(up, Box{{0, 0, -2}, {3, 3, 0.9}}));
  EXPECT_FALSE(faces_away_from(bent, Box{{0, 0, -2}, {3, 3, 0.9}}));
  // Zero-area triangles draw nothing: they neither keep nor drop the polygon, and a polygon of nothing else
  // may go; a polygon with no triangles at all is kept (nothing to decide on).
  VisPolygon flat = up;
  flat.triangles.push_back({model::Vec3{0, 0, 1}, model::Vec3{1, 0, 1}, model::Vec3{2, 0, 1}});
  EXPECT_TRUE(faces_away_from(flat, Box{{0, 0, -2}, {3, 3, 0}}));
  VisPolygon only_flat;
  only_flat.triangles = {{model::Vec3{0, 0, 1}, model::Vec3{1, 0, 1}, model::Vec3{2, 0, 1}}};
  EXPECT_TRUE(faces_away_from(only_flat, Box{{0, 0, -2}, {3, 3, 0}}));
  EXPECT_FALSE(faces_away_from(VisPolygon{}, Box{{0, 0, -2}, {3, 3, 0}}));
}

TEST(VisibilityPredicates, BoxContainsAndOverlapsOnFaces) {
  const Box b{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(b.contains({1, 1, 1}));
  EXPECT_FALSE(b.contains({1.1, 0, 0}));
  EXPECT_TRUE(b.contains({1.1, 0, 0}, 0.2));
  EXPECT_TRUE(b.overlaps(Box{{1, 0, 0}, {2, 1, 1}}, 0.0));  // sharing a face
  EXPECT_FALSE(b.overlaps(Box{{1.5, 0, 0}, {2, 1, 1}}, 0.0));
}

TEST(VisibilityPredicates, LocateOnEmptyTreeAndOnThePlane) {
  EXPECT_EQ(locate({}, {5, 5, 5}), 0u);
  model::NodeRecord n{};
  n.plane[0] = 1.0;
  n.plane[3] = -2.0;                        // x = 2
  n.front = -1;                             // cell 0
  n.back = -2;                              // cell 1
  EXPECT_EQ(locate({n}, {2.0, 0, 0}), 0u);  // on the plane: front, as Bundle::locate_cell
  EXPECT_EQ(locate({n}, {1.999, 0, 0}), 1u);
}

TEST(VisibilityPredicates, OpenRegionDropsCracksKeepsDoors) {
  const double s = kAxialClipperScale;
  auto r = [&](double x0, double x1, double y0, double y1) {
    return ClipperLib::Path{{ClipperLib::cInt(x0 * s), ClipperLib::cInt(y0 * s)},
                            {ClipperLib::cInt(x1 * s), ClipperLib::cInt(y0 * s)},
                            {ClipperLib::cInt(x1 * s), ClipperLib::cInt(y1 * s)},
                            {ClipperLib::cInt(x0 * s), ClipperLib::cInt(y1 * s)}};
  };
  EXPECT_TRUE(open_region({r(0, 1e-4, 0, 3)}, 5e-4).empty());           // 0.1 mm crack
  EXPECT_NEAR(area_of(open_region({r(0, 1, 0, 2)}, 5e-4)), 2.0, 1e-6);  // a door stays whole
  EXPECT_TRUE(open_region({}, 5e-4).empty());
}

// Does the convex planar winding `w` hold `p` (in its plane) to `tol` metres?
bool holds(const Winding& w, const model::Vec3& p, double tol) {
  if (w.size() < 3) return false;
  model::Vec3 n{0.0};
  for (std::size_t i = 1; i + 1 < w.size(); ++i) n += glm::cross(w[i] - w[0], w[i + 1] - w[0]);
  n = glm::normalize(n);
  for (std::size_t i = 0; i < w.size(); ++i) {
    const model::Vec3 inward = glm::normalize(glm::cross(n, w[(i + 1) % w.size()] - w[i]));
    if (glm::dot(inward, p - w[i]) < -tol) return false;
  }
  return true;
}

Winding square_at(double z, double lo, double hi) {
  return {{lo, lo, z}, {hi, lo, z}, {hi, hi, z}, {lo, hi, z}};
}

// Sight lines from the source through the unit window in z = 0, to the plane z = dest_z below: every one
// lands in what reached_through keeps of a square there, however far the square lies past a window close
// to the source (the slack a far target multiplies). Corner to corner lines are the grazing ones.
void expect_every_line_kept(const std::vector<model::Vec3>& source, const Box& source_box, double dest_z,
                            double half) {
  const Winding dest = square_at(dest_z, -half, half);
  const Winding kept = reached_through(source, kSquare, dest);
  ASSERT_GE(kept.size(), 3u);
  EXPECT_LT(area(kept), 0.5 * area(dest)) << "the far square is cut down to the lines' reach";
  auto landing = [&](const model::Vec3& s, const model::Vec3& w) {
    return s + (w - s) * ((dest_z - s.z) / (w.z - s.z));
  };
  for (const auto& s : source)
    for (const auto& w : kSquare) EXPECT_TRUE(holds(kept, landing(s, w), kPlaneEpsilon)) << dest_z;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const model::Vec3 s = source_box.min + model::Vec3{u(rng), u(rng), u(rng)} * source_box.size();
    const model::Vec3 w{u(rng), u(rng), 0.0};
    ASSERT_TRUE(holds(kept, landing(s, w), kPlaneEpsilon)) << "line " << i << ", dest z " << dest_z;
  }
}

TEST(VisibilityPredicates, ReachedThroughAWindowKeepsEveryLineFromTheSource) {
  // A box over the window, and a flat portal 1 cm over it with the far square 100 m down, where the lines
  // spread 7.5 km either way: the slack a far target multiplies by 10^4.
  const Box over{{-1.0, -1.0, 1.0}, {2.0, 2.0, 2.0}};
  expect_every_line_kept(box_corners(over), over, -3.0, 50.0);
  const Box portal{{0.25, 0.25, 1e-2}, {0.75, 0.75, 1e-2}};
  const Winding flat = square_at(1e-2, 0.25, 0.75);
  expect_every_line_kept(flat, portal, -100.0, 2e4);
}

TEST(VisibilityPredicates, ReachedThroughDegenerateCases) {
  const std::vector<model::Vec3> over = box_corners(Box{{-1.0, -1.0, 1.0}, {2.0, 2.0, 2.0}});
  // Past every line's reach (at z = -3 they land within x -5..8): nothing.
  EXPECT_TRUE(
      reached_through(over, kSquare, Winding{{20, 0, -3}, {21, 0, -3}, {21, 1, -3}, {20, 1, -3}}).empty());
  const Winding dest = square_at(-3.0, -50.0, 50.0);
  // A source touching the window's plane reaches round its edges at any angle: the square stays whole.
  const std::vector<model::Vec3> touching = box_corners(Box{{-1.0, -1.0, 0.0}, {2.0, 2.0, 1.0}});
  EXPECT_EQ(reached_through(touching, kSquare, dest), dest);
  // A window of collinear points, an empty source, a dest of two points: left as they are.
  EXPECT_EQ(reached_through(over, Winding{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, dest), dest);
  EXPECT_EQ(reached_through({}, kSquare, dest), dest);
  const Winding segment{{0, 0, -3}, {1, 0, -3}};
  EXPECT_EQ(reached_through(over, kSquare, segment), segment);
}

}  // namespace test_visibility_predicates
}  // namespace walk::compiler
