// The final gather (compiler/lighting/final_gather.hpp): a receiver inside a box of uniform radiosity
// reflects exactly albedo x radiosity; one lit face gives the closed-form form factor; a dark receiver's
// noise is judged against the room's light; rays that leave the model or meet a surface's back bring
// nothing, and a receiver most of whose rays do is hidden; receivers on a polygon's edge move into it,
// others stay.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "compiler/lighting/final_gather.hpp"

namespace walk::compiler {
namespace test_final_gather {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;

// Adds quad a b c d (counter-clockwise about its normal) as two patches of polygon `polygon`.
void add_quad(PatchSet& set, const std::array<Vec3, 4>& q, std::uint32_t polygon) {
  const auto first = static_cast<std::uint32_t>(set.vertices.size());
  for (const Vec3& v : q) set.vertices.push_back(v);
  ASSERT_TRUE(set.add(first, first + 1, first + 2, model::Rgb(0.5), polygon));
  ASSERT_TRUE(set.add(first, first + 2, first + 3, model::Rgb(0.5), polygon));
}

// A 2 m box, every face turned inwards; the ceiling (z = 2) is polygon 1, the rest polygon 0.
PatchSet box() {
  PatchSet set;
  add_quad(set, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)}, 0);  // floor, +z
  add_quad(set, {Vec3(0, 0, 2), Vec3(0, 2, 2), Vec3(2, 2, 2), Vec3(2, 0, 2)}, 1);  // ceiling, -z
  add_quad(set, {Vec3(0, 0, 0), Vec3(0, 2, 0), Vec3(0, 2, 2), Vec3(0, 0, 2)}, 0);  // x = 0, +x
  add_quad(set, {Vec3(2, 0, 0), Vec3(2, 0, 2), Vec3(2, 2, 2), Vec3(2, 2, 0)}, 0);  // x = 2, -x
  add_quad(set, {Vec3(0, 0, 0), Vec3(0, 0, 2), Vec3(2, 0, 2), Vec3(2, 0, 0)}, 0);  // y = 0, +y
  add_quad(set, {Vec3(0, 2, 0), Vec3(2, 2, 0), Vec3(2, 2, 2), Vec3(0, 2, 2)}, 0);  // y = 2, -y
  return set;
}

// Outgoing light `rgb` on circuit 0 for the patches of `polygon` (every polygon when it is -1).
SparseLight outgoing(const PatchSet& set, double rgb, int polygon = -1) {
  SparseLight out(set.patches.size());
  for (std::size_t p = 0; p < set.patches.size(); ++p)
    if (polygon < 0 || set.patches[p].polygon == std::uint32_t(polygon)) {
      double* b = out.at(p, 0);
      b[0] = b[1] = b[2] = rgb;
    }
  return out;
}

const SurfaceSample kFloorCentre{Vec3(1, 1, 0), Vec3(0, 0, 1), model::Rgb(0.5)};

TEST(FinalGather, AUniformBoxReflectsAlbedoTimesRadiosityAtTheFewestRays) {
  const PatchSet set = box();
  const std::vector<SurfaceSample> samples{kFloorCentre};
  const std::vector<double> direct{0.0};
  FinalGatherStats stats;
  const SparseLight light = gather_indirect(set, outgoing(set, 2.0), samples, direct, {}, &stats);
  ASSERT_EQ(light.row(0).size(), 1u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(light.row(0)[0].rgb[c], 1.0, 1e-12);
  // Every ray brings the same light: no spread, so the target is met at the fewest batches.
  EXPECT_EQ(stats.rays, std::uint64_t(kGatherMinBatches * kGatherBatchRays));
  EXPECT_EQ(stats.capped, 0u);
  EXPECT_NEAR(stats.estimated_error, 0.0, 1e-12);
  EXPECT_NEAR(stats.gathered_share, 1.0, 1e-12);
}

TEST(FinalGather, OneLitFaceGivesTheFormFactor) {
  // Only the ceiling sends light (B = 1): the floor's centre reflects albedo x F, F the form factor from a
  // point to a 2 m square 2 m above its centre: 4 corner rectangles of X = Y = 1/2.
  const PatchSet set = box();
  const double x = 0.5, s = std::sqrt(1.0 + x * x);
  const double f = 4.0 * (2.0 * x / s * std::atan(x / s)) / (2.0 * std::numbers::pi);  // 0.2394
  FinalGatherOptions o;
  o.target_error = 0.01;
  FinalGatherStats stats;
  const SparseLight light =
      gather_indirect(set, outgoing(set, 1.0, 1), std::vector{kFloorCentre}, std::vector{0.0}, o, &stats);
  ASSERT_EQ(light.row(0).size(), 1u);
  const double shown = light.row(0)[0].rgb[1];
  EXPECT_NEAR(shown, 0.5 * f, 0.04 * 0.5 * f);
  // The estimate is honest (within three of its standard errors of the closed form) and the spread asked
  // for more than the fewest rays: the target met, or the cap reached and counted.
  EXPECT_LE(std::abs(shown - 0.5 * f), 3.0 * stats.estimated_error * shown);
  EXPECT_GT(stats.rays, std::uint64_t(kGatherMinBatches * kGatherBatchRays));
  if (stats.capped == 0)
    EXPECT_LE(stats.estimated_error, 0.01);
  else
    EXPECT_EQ(stats.rays, std::uint64_t(kGatherMaxBatches * kGatherBatchRays));
}

TEST(FinalGather, ADarkReceiverIsJudgedAgainstTheRoomsLight) {
  // The same receiver beside a brightly lit one: its light (0.12) is far below a quarter of the RMS direct
  // light (0.25 x 100 / sqrt 2), so its noise is judged against that and it stops at the fewest rays.
  const PatchSet set = box();
  FinalGatherOptions o;
  o.target_error = 0.01;
  FinalGatherStats stats;
  const std::vector<SurfaceSample> samples{kFloorCentre, kFloorCentre};
  const SparseLight light =
      gather_indirect(set, outgoing(set, 1.0, 1), samples, std::vector{0.0, 100.0}, o, &stats);
  EXPECT_EQ(stats.rays, std::uint64_t(2 * kGatherMinBatches * kGatherBatchRays));
  EXPECT_EQ(stats.capped, 0u);
  ASSERT_EQ(light.row(0).size(), 1u);
  EXPECT_GT(light.row(0)[0].rgb[0], 0.0);
}

TEST(FinalGather, RaysOutOfTheModelOrOntoABackBringNothing) {
  // One square at z = 1 facing up (+z), sending B = 5. Below it, facing up, a receiver meets only its back
  // or nothing; above it, facing down, a receiver sees its front.
  PatchSet set;
  add_quad(set, {Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(2, 2, 1), Vec3(0, 2, 1)}, 0);
  const std::vector<SurfaceSample> samples{{Vec3(1, 1, 0), Vec3(0, 0, 1), model::Rgb(0.5)},
                                           {Vec3(1, 1, 2), Vec3(0, 0, -1), model::Rgb(0.5)}};
  const SparseLight light = gather_indirect(set, outgoing(set, 5.0), samples, std::vector{0.0, 0.0}, {});
  EXPECT_TRUE(light.row(0).empty());
  ASSERT_EQ(light.row(1).size(), 1u);
  EXPECT_GT(light.row(1)[0].rgb[0], 0.0);
  EXPECT_LT(light.row(1)[0].rgb[0], 2.5);  // below albedo x B: part of its hemisphere sees nothing
}

TEST(FinalGather, AReceiverJustBehindASurfaceIsHidden) {
  // 2 cm under the square's back (a ceiling above a lamp's panel), nearly every ray meets that back: no
  // view sees the receiver. Inside the box every ray meets a front.
  PatchSet set;
  add_quad(set, {Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(2, 2, 1), Vec3(0, 2, 1)}, 0);
  const std::vector<SurfaceSample> under{{Vec3(1, 1, 0.98), Vec3(0, 0, 1), model::Rgb(0.5)},
                                         {Vec3(1, 1, 2), Vec3(0, 0, -1), model::Rgb(0.5)}};
  FinalGatherStats stats;
  (void)gather_indirect(set, outgoing(set, 5.0), under, std::vector{0.0, 0.0}, {}, &stats);
  EXPECT_EQ(stats.hidden, (std::vector<std::uint8_t>{1, 0}));
  const PatchSet room = box();
  (void)gather_indirect(room, outgoing(room, 1.0), std::vector{kFloorCentre}, std::vector{0.0}, {}, &stats);
  EXPECT_EQ(stats.hidden, (std::vector<std::uint8_t>{0}));
}

TEST(FinalGather, ReceiversOnAnEdgeMoveIntoTheirPolygonAndOthersStay) {
  // A unit square fanned round its centre: the corner (0, 0) moves kGatherInset along the diagonal into
  // the square; the centre, with triangles all round it, stays.
  const std::vector<Vec3> vertices{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                   Vec3(0.5, 0.5, 0)};
  const std::vector<std::uint32_t> indices{0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  std::vector<SurfaceSample> samples{{vertices[0], Vec3(0, 0, 1), model::Rgb(0.5)},
                                     {vertices[4], Vec3(0, 0, 1), model::Rgb(0.5)}};
  inset_from_edges(samples, std::vector<std::uint32_t>{0, 4}, vertices, indices);
  const Vec3 moved = samples[0].position;
  EXPECT_NEAR(std::hypot(moved.x, moved.y), kGatherInset, 1e-12);
  EXPECT_NEAR(moved.x, moved.y, 1e-12);
  EXPECT_GT(moved.x, 0.0);
  EXPECT_EQ(moved.z, 0.0);
  EXPECT_EQ(samples[1].position, vertices[4]);
}

}  // namespace test_final_gather
}  // namespace walk::compiler
