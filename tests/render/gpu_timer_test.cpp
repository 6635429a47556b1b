// Frame timing by GL timer queries: the timer hands each frame back with its tag and a time, never blocks
// on a frame still in flight beyond its ring, and the renderer feeds the governor from it when asked (on
// software rasterizers Auto keeps glFinish: see render/gpu_timer.hpp).
#include "render/gpu_timer.hpp"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace gpu_timer_test {  // named, not anonymous: the suite compiles as unity batches

TEST(FrameTiming, NamesParse) {
  EXPECT_EQ(parse_frame_timing("auto"), FrameTiming::Auto);
  EXPECT_EQ(parse_frame_timing("finish"), FrameTiming::Finish);
  EXPECT_EQ(parse_frame_timing("queries"), FrameTiming::Queries);
  EXPECT_EQ(parse_frame_timing("gpu"), std::nullopt);
  EXPECT_EQ(parse_frame_timing(""), std::nullopt);
}

class GpuTimerTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override {
    backend_ = headless(GetParam());
    if (!timer_queries_supported()) GTEST_SKIP() << "this driver's timer queries have no counter bits";
  }
  std::unique_ptr<Backend> backend_;
};

TEST_P(GpuTimerTest, FramesComeBackInOrderWithTheirTags) {
  GpuTimer timer;
  EXPECT_FALSE(timer.ready());  // nothing timed yet
  for (std::uint32_t i = 0; i < 3; ++i) {
    timer.begin();
    glClearColor(0.1f * float(i), 0.2f, 0.3f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    timer.end({true, i, std::uint8_t(i), 100.0 * i, 1, 0.5});
  }
  glFinish();  // every query's result is available now
  std::uint32_t next = 0;
  while (auto done = timer.ready()) {
    EXPECT_GE(done->first.cell, next);  // oldest first
    next = done->first.cell + 1;
    EXPECT_EQ(done->first.triangles, 100.0 * done->first.cell);
    EXPECT_GE(done->second, 0.0);
    EXPECT_LT(done->second, 10'000.0);  // milliseconds, not nanoseconds
  }
  EXPECT_EQ(next, 3u);              // the last frame came back
  EXPECT_LE(timer.rejected(), 1u);  // llvmpipe's first query over a bare clear is nonsense, and dropped
}

TEST_P(GpuTimerTest, MoreFramesThanTheRingDropTheOldestInsteadOfBlockingForever) {
  GpuTimer timer;
  constexpr std::uint32_t kFrames = GpuTimer::kInFlight + 3;
  for (std::uint32_t i = 0; i < kFrames; ++i) {
    timer.begin();
    glClear(GL_COLOR_BUFFER_BIT);
    timer.end({true, i, 0, -1.0, 1, 0.0});
  }
  glFinish();
  std::uint32_t first = kFrames, count = 0;
  while (auto done = timer.ready()) {
    first = std::min(first, done->first.cell);
    ++count;
  }
  EXPECT_EQ(count, GpuTimer::kInFlight);            // the newest kInFlight frames ...
  EXPECT_EQ(first, kFrames - GpuTimer::kInFlight);  // ... the older ones waited for and dropped
}

TEST_P(GpuTimerTest, RendererTimedByQueriesTeachesTheGovernor) {
  auto bundle = open_two_rooms(TwoRooms{}, "gpu_timer");
  Renderer renderer(*bundle);
  EXPECT_EQ(renderer.timing_by_queries(), !software_rasterizer());  // Auto
  renderer.set_frame_timing(FrameTiming::Finish);
  EXPECT_FALSE(renderer.timing_by_queries());
  renderer.set_frame_timing(FrameTiming::Queries);
  ASSERT_TRUE(renderer.timing_by_queries());
  renderer.set_moving_level(MovingLevel::Coarse);
  for (int i = 0; i < 12; ++i) {  // a walk: every frame moving
    View view = looking_along_x(+1.0, 1.0 + 0.05 * i);
    ASSERT_TRUE(renderer.refine(view, kWidth, kHeight));
    glFinish();  // as a present would: the queries of earlier frames are ready by the next
  }
  EXPECT_GE(renderer.last_stats().gpu_ms, 0.0);
  EXPECT_GE(renderer.governor().estimate(renderer.last_stats().cell, MovingLevel::Coarse), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Headless, GpuTimerTest, ::testing::Values(BackendKind::OSMesa, BackendKind::EGL),
                         [](const auto& info) { return std::string(backend_kind_name(info.param)); });

}  // namespace gpu_timer_test
}  // namespace walk::render::test
