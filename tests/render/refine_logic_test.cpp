// Adaptive refinement's CPU parts alone: the schedule's steps, the jitter pattern and the governor's choices
// from given frame times (no clock, no GL).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <set>
#include <vector>

#include "render/diagonals.hpp"
#include "render/governor.hpp"
#include "render/jitter.hpp"
#include "render/refine_schedule.hpp"
#include "render/subdivision.hpp"

namespace walk::render {
namespace refine_logic_test {  // named, not anonymous: the suite compiles as unity batches

// A still frame's slice for diagonals and sub-quads leaves time to draw it: the cap before any sample is
// measured or when drawing is quick, the budget's rest after a slow sample, and the cap again where the
// drawing alone leaves less than the least slice (the frame misses anyway: as few such frames as may be).
TEST(FrameGovernor, StillSliceLeavesTimeToDrawTheFrame) {
  FrameGovernor governor(60.0);
  EXPECT_EQ(governor.still_slice_ms(8.0), 8.0) << "nothing measured yet";
  governor.record_sample(1.0);
  EXPECT_EQ(governor.still_slice_ms(8.0), 8.0) << "a quick sample leaves the cap";
  FrameGovernor slow(60.0);
  slow.record_sample(11.5);  // the generated L building's 16-sample still view
  const double slice = slow.still_slice_ms(8.0);
  EXPECT_LT(slice, 8.0);
  EXPECT_NEAR(slice + 11.5, 0.9 * 1000.0 / 60.0, 1e-9) << "the slice and the sample fill the budget's 90 %";
  FrameGovernor slower(60.0);
  slower.record_sample(0.9 * 1000.0 / 60.0 - 1.5);
  EXPECT_NEAR(slower.still_slice_ms(8.0), 1.5, 1e-9) << "just above the least slice";
  EXPECT_EQ(slower.still_slice_ms(0.5), 0.5) << "a cap below what is left wins";
  FrameGovernor too_slow(60.0);
  too_slow.record_sample(0.9 * 1000.0 / 60.0 - 0.5);
  EXPECT_EQ(too_slow.still_slice_ms(8.0), 8.0) << "less than the least slice left: the frame misses anyway";
}

// The slice leaves time for the larger of the view's last still draw and a sample; before either, for what
// the moving frames showed drawing costs: the full-detail level's mean, or the last moving frame when no
// full-detail frame was drawn (or it was slower).
TEST(FrameGovernor, SliceLeavesTimeForTheStillDrawOrWhatStandsForIt) {
  const double budget = 0.9 * 1000.0 / 60.0;  // the budget less its headroom
  FrameGovernor governor(60.0);
  EXPECT_LT(governor.expected_still_draw_ms(), 0.0);
  governor.record_moving(0, MovingLevel::Coarse, 12.0);
  EXPECT_DOUBLE_EQ(governor.expected_still_draw_ms(), 12.0);
  EXPECT_NEAR(governor.still_slice_ms(8.0), budget - 12.0, 1e-9);
  for (int k = 0; k < 4; ++k) {
    governor.record_moving(1, MovingLevel::Patches, 13.0, 1000.0);
    governor.record_moving(1, MovingLevel::Patches, 14.0, 1000.0);
  }
  governor.record_moving(2, MovingLevel::Reduced, 4.0);
  EXPECT_NEAR(governor.expected_still_draw_ms(), 13.5, 0.01)
      << "the full-detail mean (decayed), not the cheap last frame";
  EXPECT_NEAR(governor.still_slice_ms(8.0), budget - 13.5, 0.01);
  governor.record_moving(2, MovingLevel::Coarse, 30.0);
  EXPECT_EQ(governor.still_slice_ms(8.0), 8.0) << "a slower last frame counts: it cannot fit, so the cap";
  governor.record_sample(12.5);
  EXPECT_NEAR(governor.still_slice_ms(8.0), budget - 12.5, 1e-9) << "a measured sample replaces the guess";
  governor.record_still_draw(2.0);
  EXPECT_NEAR(governor.still_slice_ms(8.0), budget - 12.5, 1e-9) << "the larger of still draw and sample";
  governor.record_still_draw(14.0);
  EXPECT_NEAR(governor.still_slice_ms(8.0), budget - 14.0, 1e-9);
  FrameGovernor drawn_only(60.0);
  drawn_only.record_moving(0, MovingLevel::Coarse, 30.0);
  drawn_only.record_still_draw(2.0);
  EXPECT_EQ(drawn_only.still_slice_ms(8.0), 8.0) << "a measured still draw replaces the moving frames' guess";
}

// A Diagonals step that ran out of its time slice is followed by another; accumulation starts after the
// one that finishes.
TEST(RefineSchedule, UnfinishedDiagonalsRepeatBeforeAccumulation) {
  RefineSchedule schedule({.blend_steps = 0, .aa_samples = 2});
  schedule.view_changed(1.0f);
  EXPECT_EQ(schedule.next().stage, RefineStage::Moving);
  for (int k = 0; k < 3; ++k) {
    const RefineStep step = schedule.next();
    ASSERT_EQ(step.stage, RefineStage::Diagonals) << k;
    EXPECT_TRUE(step.diagonals);
    schedule.diagonals_unfinished();
  }
  EXPECT_EQ(schedule.next().stage, RefineStage::Diagonals);
  const RefineStep first = schedule.next();
  EXPECT_EQ(first.stage, RefineStage::Accumulating);
  EXPECT_EQ(first.sample, 0);
  schedule.diagonals_unfinished();  // too late: accumulation has begun and its samples keep their geometry
  EXPECT_EQ(schedule.next().sample, 1);
  EXPECT_FALSE(schedule.next().draws());
}

TEST(RefineSchedule, MovingThenBlendThenSamplesThenIdle) {
  RefineSchedule schedule({.blend_steps = 50, .aa_samples = 8});
  schedule.view_changed(0.0f);
  RefineStep step = schedule.next();
  EXPECT_EQ(step.stage, RefineStage::Moving);
  EXPECT_EQ(step.patch_weight, 0.0f);
  float last = 0.0f;
  for (int i = 1; i <= 50; ++i) {
    step = schedule.next();
    ASSERT_EQ(step.stage, RefineStage::Blending) << i;
    EXPECT_GT(step.patch_weight, last);
    last = step.patch_weight;
  }
  EXPECT_EQ(last, 1.0f);
  step = schedule.next();
  EXPECT_EQ(step.stage, RefineStage::Diagonals);
  EXPECT_TRUE(step.diagonals);
  for (int s = 0; s < 8; ++s) {
    step = schedule.next();
    ASSERT_EQ(step.stage, RefineStage::Accumulating);
    EXPECT_EQ(step.sample, s);
    EXPECT_TRUE(step.diagonals);
  }
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(schedule.next().draws());
}

TEST(RefineSchedule, MovingAtPatchesSkipsTheBlend) {
  RefineSchedule schedule({.blend_steps = 50, .aa_samples = 2, .samples_per_frame = 0, .diagonals = false});
  schedule.view_changed(1.0f);
  EXPECT_EQ(schedule.next().stage, RefineStage::Moving);
  EXPECT_EQ(schedule.next().stage, RefineStage::Accumulating);
}

TEST(RefineSchedule, LightChangeRestartsSamplesNotTheBlend) {
  RefineSchedule schedule({.blend_steps = 4, .aa_samples = 3});
  schedule.view_changed(0.0f);
  for (int i = 0; i < 1 + 4 + 1 + 3; ++i) (void)schedule.next();
  EXPECT_FALSE(schedule.next().draws());
  schedule.light_changed();
  const RefineStep relit = schedule.next();
  EXPECT_EQ(relit.stage, RefineStage::Relit) << "first the new mix as a plain patch frame";
  EXPECT_EQ(relit.patch_weight, 1.0f);
  EXPECT_FALSE(relit.diagonals);
  schedule.light_changed();  // the dimmer is still being turned: another plain frame
  EXPECT_EQ(schedule.next().stage, RefineStage::Relit);
  EXPECT_EQ(schedule.next().stage, RefineStage::Diagonals) << "the new mix needs its own diagonals";
  const RefineStep step = schedule.next();
  EXPECT_EQ(step.stage, RefineStage::Accumulating);
  EXPECT_EQ(step.sample, 0);
  EXPECT_EQ(step.patch_weight, 1.0f);
}

TEST(RefineSchedule, WithoutDiagonalsALightChangeGoesStraightToTheSamples) {
  RefineSchedule schedule({.blend_steps = 0, .aa_samples = 2, .samples_per_frame = 0, .diagonals = false});
  schedule.view_changed(1.0f);
  for (int i = 0; i < 1 + 2; ++i) (void)schedule.next();
  EXPECT_FALSE(schedule.next().draws());
  schedule.light_changed();
  const RefineStep step = schedule.next();
  EXPECT_EQ(step.stage, RefineStage::Accumulating);
  EXPECT_EQ(step.sample, 0) << "sample 0 is the plain patch frame";
}

TEST(Jitter, FirstSampleIsThePixelCentreAndWeightsAreTheTent) {
  const auto samples = jitter_pattern(16);
  ASSERT_EQ(samples.size(), 16u);
  EXPECT_EQ(samples[0].dx, 0.0f);
  EXPECT_EQ(samples[0].weight, 1.0f);
  double mean_x = 0.0, mean_y = 0.0;
  for (const auto& s : samples) {
    EXPECT_LE(std::abs(s.dx), 1.0f);
    EXPECT_LE(std::abs(s.dy), 1.0f);
    EXPECT_NEAR(s.weight, (1 - std::abs(s.dx)) * (1 - std::abs(s.dy)), 1e-6);
    mean_x += s.dx / 16.0;
    mean_y += s.dy / 16.0;
  }
  // Stratified: the samples are centred on the pixel (no drift of the image).
  EXPECT_LT(std::abs(mean_x), 0.25);
  EXPECT_LT(std::abs(mean_y), 0.25);
  EXPECT_EQ(jitter_pattern(16)[7].dx, samples[7].dx) << "deterministic";
}

TEST(FrameGovernor, ChoosesPatchesOnlyWhereTheyFitPerCell) {
  FrameGovernor governor(60.0);
  EXPECT_NEAR(governor.budget_ms(), 16.667, 0.01);
  EXPECT_EQ(governor.choose_moving(0), MovingLevel::Patches) << "nothing known: try the better level";
  governor.record_moving(0, MovingLevel::Patches, 30.0);
  EXPECT_EQ(governor.choose_moving(0), MovingLevel::Coarse) << "30 ms does not fit 16.7 ms";
  governor.record_moving(1, MovingLevel::Patches, 8.0);
  EXPECT_EQ(governor.choose_moving(1), MovingLevel::Patches) << "cells are judged apart";
  governor.record_moving(2, MovingLevel::Coarse, 15.0);
  EXPECT_EQ(governor.choose_moving(2), MovingLevel::Coarse) << "coarse barely fits: do not try patches";
  // A cell that got cheaper comes back up as measurements arrive.
  for (int i = 0; i < 20; ++i) governor.record_moving(0, MovingLevel::Patches, 5.0);
  EXPECT_EQ(governor.choose_moving(0), MovingLevel::Patches);
}

TEST(FrameGovernor, ANewCellStartsAtTheLevelOfTheCellJustLeft) {
  FrameGovernor governor(60.0);
  EXPECT_EQ(governor.choose_moving(3), MovingLevel::Patches);
  governor.record_moving(3, MovingLevel::Patches, 40.0);
  governor.record_moving(3, MovingLevel::Coarse, 12.0);
  EXPECT_EQ(governor.choose_moving(3), MovingLevel::Coarse);
  EXPECT_EQ(governor.choose_moving(7), MovingLevel::Coarse) << "cell 7 unknown: judged as cell 3";
  governor.record_moving(7, MovingLevel::Coarse, 3.0);
  EXPECT_EQ(governor.choose_moving(7), MovingLevel::Patches) << "its own cheap frame: try patches there";
}

TEST(FrameGovernor, SimplifiedComesBeforeHalfResolutionWhichIsTheFloor) {
  FrameGovernor governor(60.0);
  governor.record_moving(4, MovingLevel::Patches, 40.0);
  governor.record_moving(4, MovingLevel::Coarse, 25.0);
  EXPECT_EQ(governor.choose_moving(4), MovingLevel::Simplified) << "fewer triangles before fewer pixels";
  governor.record_moving(4, MovingLevel::Simplified, 20.0);
  EXPECT_EQ(governor.choose_moving(4), MovingLevel::Reduced);
  governor.record_moving(4, MovingLevel::Reduced, 18.0);
  EXPECT_EQ(governor.choose_moving(4), MovingLevel::Reduced) << "nothing fits: the cheapest, the floor";
  // Reduced known cheap and the levels above it never tried: try the one above.
  governor.record_moving(5, MovingLevel::Patches, 40.0);
  governor.record_moving(5, MovingLevel::Reduced, 4.0);
  EXPECT_EQ(governor.choose_moving(5), MovingLevel::Coarse);
  governor.record_moving(5, MovingLevel::Coarse, 30.0);
  EXPECT_EQ(governor.choose_moving(5), MovingLevel::Simplified);
}

TEST(FrameGovernor, HalfResolutionOnlyWhereItIsCheaper) {
  // A large model's frame that is not fill-bound: half resolution costs what the simplified level does.
  FrameGovernor governor(60.0);
  governor.record_moving(4, MovingLevel::Patches, 40.0);
  governor.record_moving(4, MovingLevel::Coarse, 25.0);
  governor.record_moving(4, MovingLevel::Simplified, 20.0);
  governor.record_moving(4, MovingLevel::Reduced, 21.0);
  EXPECT_EQ(governor.choose_moving(4), MovingLevel::Simplified) << "nothing fits; simplified is cheapest";
  governor.record_moving(9, MovingLevel::Patches, 40.0);
  governor.record_moving(9, MovingLevel::Coarse, 20.0);
  governor.record_moving(9, MovingLevel::Simplified, 20.0);
  governor.record_moving(9, MovingLevel::Reduced, 20.0);
  EXPECT_EQ(governor.choose_moving(9), MovingLevel::Coarse) << "a tie goes to the better picture";
  // Judged by the cost models (M's frames: half resolution predicted 12.97 + 2 x 1.77 ms, simplified
  // 11.12 + 2 x 1.91 ms, neither within 90 % of the budget): simplified, not the floor.
  FrameGovernor modelled(60.0);
  for (int i = 0; i < 20; ++i) {
    const double t = 10000.0 + 100.0 * (i % 3);
    modelled.record_moving(1, MovingLevel::Reduced, i % 2 ? 14.0 : 16.0, t);
    modelled.record_moving(1, MovingLevel::Simplified, i % 2 ? 13.5 : 15.5, t);
    modelled.record_moving(1, MovingLevel::Patches, 40.0, 8.0 * t);
  }
  const std::array<double, kMovingLevels> view{10100.0, 10100.0, 50000.0, 80000.0};
  EXPECT_EQ(modelled.choose_moving(2, view), MovingLevel::Simplified);
}

TEST(FrameGovernor, ProbesTheNextLevelUpNowAndThen) {
  FrameGovernor governor(60.0);
  governor.record_moving(6, MovingLevel::Patches, 40.0);
  governor.record_moving(6, MovingLevel::Coarse, 40.0);
  governor.record_moving(6, MovingLevel::Simplified, 40.0);  // one slow frame on a busy CPU
  governor.record_moving(6, MovingLevel::Reduced, 5.0);
  int probes = 0;
  for (int i = 1; i <= 2 * FrameGovernor::kProbeInterval; ++i) {
    const MovingLevel level = governor.choose_moving(6);
    if (level != MovingLevel::Reduced) {
      EXPECT_EQ(level, MovingLevel::Simplified) << "one level up, not two";
      EXPECT_EQ(i % FrameGovernor::kProbeInterval, 0) << "choice " << i;
      ++probes;
    }
  }
  EXPECT_EQ(probes, 2);
  // The probe measured simplified as cheap now: the estimate follows and it is chosen from then on.
  for (int i = 0; i < 10; ++i) governor.record_moving(6, MovingLevel::Simplified, 6.0);
  EXPECT_EQ(governor.choose_moving(6), MovingLevel::Simplified);
}

TEST(FrameGovernor, PredictsALevelsCostFromTheTrianglesItWillDraw) {
  FrameGovernor governor(60.0);
  EXPECT_LT(governor.predict(MovingLevel::Patches, 1000.0), 0.0) << "no frames yet";
  // Patches cost 1 ms + 1 ms per thousand triangles, measured in cell 1 only.
  for (int i = 0; i < 20; ++i) {
    const double t = 2000.0 + 500.0 * (i % 5);
    governor.record_moving(1, MovingLevel::Patches, 1.0 + t / 1000.0, t);
  }
  EXPECT_NEAR(governor.predict(MovingLevel::Patches, 10000.0), 11.0, 1e-6);
  EXPECT_NEAR(governor.predict(MovingLevel::Patches, 30000.0), 31.0, 1e-6);
  EXPECT_LT(governor.predict(MovingLevel::Coarse, 1000.0), 0.0) << "each level has a model of its own";
  // Cell 1's patch frames were cheap, so a new cell would inherit Patches; judged by what this view draws
  // (30,000 patch triangles), Patches is over the budget and the next level, never tried, is the choice.
  const std::array<double, kMovingLevels> heavy{500.0, 1000.0, 4000.0, 30000.0};
  EXPECT_EQ(governor.choose_moving(2, heavy), MovingLevel::Coarse);
  const std::array<double, kMovingLevels> light{500.0, 1000.0, 4000.0, 9000.0};
  EXPECT_EQ(governor.choose_moving(2, light), MovingLevel::Patches);
}

TEST(FrameGovernor, AModelThatMissesWidelyIsJudgedByItsSpreadToo) {
  FrameGovernor steady(60.0), noisy(60.0);
  for (int i = 0; i < 40; ++i) {
    const double t = 10000.0 + 100.0 * (i % 3);
    steady.record_moving(1, MovingLevel::Patches, 13.0, t);
    noisy.record_moving(1, MovingLevel::Patches, i % 2 ? 9.0 : 17.0, t);  // the same mean, +-4 ms
  }
  const std::array<double, kMovingLevels> view{500.0, 1000.0, 4000.0, 10100.0};
  EXPECT_EQ(steady.choose_moving(2, view), MovingLevel::Patches) << "13 ms fits 90 % of 16.7 ms";
  EXPECT_NE(noisy.choose_moving(2, view), MovingLevel::Patches) << "13 + 2 x 4 ms does not";
}

TEST(FrameGovernor, WhatTheFrameSpentBeforeDrawingComesOffTheBudget) {
  FrameGovernor governor(60.0);
  for (int i = 0; i < 20; ++i) {
    const double t = 10000.0 + 100.0 * (i % 3);
    governor.record_moving(1, MovingLevel::Patches, 12.0, t);
    governor.record_moving(1, MovingLevel::Coarse, 6.0, t / 4.0);
  }
  const std::array<double, kMovingLevels> view{500.0, 1000.0, 2500.0, 10100.0};
  EXPECT_EQ(governor.choose_moving(2, view), MovingLevel::Patches) << "12 ms fits 90 % of 16.7 ms";
  EXPECT_EQ(governor.choose_moving(2, view, 2.0), MovingLevel::Patches) << "and of 14.7";
  EXPECT_EQ(governor.choose_moving(2, view, 4.0), MovingLevel::Coarse) << "not of 12.7: a 4 ms portal walk";
  EXPECT_LT(int(governor.choose_moving(2, view, 50.0)), int(MovingLevel::Coarse))
      << "nothing measured fits: a cheaper level, never tried, or the floor";
  EXPECT_EQ(governor.choose_moving(2, view, std::nan("")), MovingLevel::Patches)
      << "no time known: none spent";
}

TEST(FrameGovernor, SamplesPerFrameFollowTheSampleCost) {
  FrameGovernor governor(60.0);
  EXPECT_EQ(governor.samples_per_frame(), 1);
  governor.record_sample(3.0);
  EXPECT_EQ(governor.samples_per_frame(), 5);  // 0.9 * 16.7 / 3
  FrameGovernor slow(60.0);
  slow.record_sample(40.0);
  EXPECT_EQ(slow.samples_per_frame(), 1) << "always at least one sample, or refinement never ends";
  slow.record_sample(std::nan(""));
  EXPECT_EQ(slow.samples_per_frame(), 1);
}

}  // namespace refine_logic_test
}  // namespace walk::render

namespace walk::render {
namespace refine_logic_test {  // named, not anonymous: the suite compiles as unity batches

// One quad 0-1-2-3 (counter-clockwise), split by the bundle along 1-3 as the compiler's dicing does.
struct OneQuad {
  std::vector<model::PolygonRecord> polygons{{0, 6, 0, 4, 0, 0, 0, 0}};
  std::vector<std::uint32_t> indices{0, 1, 3, 1, 2, 3};
};

TEST(Diagonals, QuadIsFoundWithItsCornersInOrder) {
  OneQuad q;
  const auto quads = find_quads(q.polygons, q.indices);
  ASSERT_EQ(quads.size(), 1u);
  EXPECT_EQ(quads[0].first_index, 0u);
  // Triangles (0,1,3) and (1,2,3) share 1-3: corners 0, 1, 2, 3 in some rotation, split along 1-3.
  const auto& v = quads[0].v;
  EXPECT_EQ(std::set<std::uint32_t>(v.begin(), v.end()), (std::set<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_TRUE((v[1] == 1 && v[3] == 3) || (v[1] == 3 && v[3] == 1));
}

TEST(Diagonals, SplitAlongTheEndsOfLeastColourDifference) {
  OneQuad q;
  const auto quads = find_quads(q.polygons, q.indices);
  // Corner 0 and 2 bright, 1 and 3 dark: the 1-3 split spreads the dark diagonal over both triangles; the
  // 0-2 split (ends equal) follows the light.
  std::vector<glm::vec3> colour{glm::vec3(10.0f), glm::vec3(0.0f), glm::vec3(9.0f), glm::vec3(5.0f)};
  std::vector<std::uint32_t> refined = q.indices;
  EXPECT_EQ(choose_diagonals(quads, colour, refined), 1u);
  auto has_edge = [&](std::uint32_t a, std::uint32_t b) {
    for (int t = 0; t < 2; ++t) {
      int found = 0;
      for (int k = 0; k < 3; ++k) found += refined[t * 3 + k] == a || refined[t * 3 + k] == b;
      if (found != 2) return false;
    }
    return true;
  };
  EXPECT_TRUE(has_edge(0, 2)) << "both triangles must share the 0-2 diagonal";
  // Winding kept: each triangle still counter-clockwise in the quad's corner order (0,1,2,3 positive).
  auto ccw = [](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::vec2 p[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const glm::vec2 u = p[b] - p[a], w = p[c] - p[a];
    return u.x * w.y - u.y * w.x > 0.0f;
  };
  EXPECT_TRUE(ccw(refined[0], refined[1], refined[2]));
  EXPECT_TRUE(ccw(refined[3], refined[4], refined[5]));
  // Swap the light: the bundle's diagonal comes back.
  colour = {glm::vec3(0.0f), glm::vec3(10.0f), glm::vec3(5.0f), glm::vec3(9.0f)};
  EXPECT_EQ(choose_diagonals(quads, colour, refined), 0u);
  EXPECT_TRUE(has_edge(1, 3));
}

TEST(Subdivision, DepthFollowsTheTwistAndCornersStayBilinear) {
  OneQuad q;
  const auto quads = find_quads(q.polygons, q.indices);
  std::vector<model::VertexRecord> vertices(4);
  const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) {
    vertices[k].position[0] = corners[k][0];
    vertices[k].position[1] = corners[k][1];
  }
  // Twist |16 - 0 + 16 - 0| / 4 = 8; threshold 0.6: 8 -> 2 -> 0.5, two levels, 16 sub-quads, 32 triangles.
  const std::vector<glm::vec3> colour{glm::vec3(16.0f), glm::vec3(0.0f), glm::vec3(16.0f), glm::vec3(0.0f)};
  const glm::vec3 c[4] = {colour[0], colour[1], colour[2], colour[3]};
  EXPECT_FLOAT_EQ(quad_twist(c), 8.0f);
  const Subdivision sub = subdivide(quads, vertices, colour, 0.6f, 5);
  ASSERT_EQ(sub.replaced_quads.size(), 1u);
  EXPECT_EQ(sub.triangles.size(), 32u * 3u);
  // Every emitted corner carries the bilinear value at its position.
  for (const ShadedVertex& v : sub.triangles) {
    const float x = v.position.x, y = v.position.y;
    const float bilinear = 16.0f * ((1 - x) * (1 - y) + x * y);
    EXPECT_NEAR(v.radiosity.x, bilinear, 1e-4f) << x << "," << y;
  }
  EXPECT_TRUE(subdivide(quads, vertices, colour, 9.0f, 5).replaced_quads.empty()) << "below the threshold";
  EXPECT_EQ(subdivide(quads, vertices, colour, 0.6f, 1).triangles.size(), 8u * 3u) << "depth limit";
}

TEST(Diagonals, NonConvexPairsAreNotQuads) {
  OneQuad q;
  std::vector<model::VertexRecord> vertices(4);
  // A dart: corner 3 pulled inside triangle 0-1-2. The bundle's 1-3 split is valid (both triangles
  // counter-clockwise); the 0-2 split would fold triangle 0-2-3 over 0-1-2.
  const float dart[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0.7f, 0.3f}};
  for (int k = 0; k < 4; ++k) {
    vertices[k].position[0] = dart[k][0];
    vertices[k].position[1] = dart[k][1];
  }
  EXPECT_TRUE(find_quads(q.polygons, q.indices, vertices).empty());
  const float square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) {
    vertices[k].position[0] = square[k][0];
    vertices[k].position[1] = square[k][1];
  }
  EXPECT_EQ(find_quads(q.polygons, q.indices, vertices).size(), 1u);
}

TEST(Diagonals, TrianglesThatAreNotPairsAreLeftAlone) {
  std::vector<model::PolygonRecord> polygons{{0, 6, 0, 6, 0, 0, 0, 0}};
  std::vector<std::uint32_t> indices{0, 1, 2, 3, 4, 5};
  EXPECT_TRUE(find_quads(polygons, indices).empty());
}

}  // namespace refine_logic_test
}  // namespace walk::render
