// walkd's PNG saver: frames written whole off the calling thread, a bounded queue that drops rather than
// grows, and a failed write that is counted and leaves nothing behind.
#include "firmware-host/frame_saver.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace walk::kiosk {
namespace frame_saver_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

render::Image noise(int width, int height) {
  render::Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4)};
  std::mt19937 random(7);
  for (auto& byte : image.rgba) byte = static_cast<std::uint8_t>(random());  // incompressible: slow to encode
  return image;
}

class FrameSaverTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("walk_frame_saver_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FrameSaverTest, WritesEveryQueuedFrameWholeByFlush) {
  FrameSaver saver;
  EXPECT_TRUE(saver.save((dir_ / "a.png").string(), noise(8, 4)));
  saver.flush();
  EXPECT_TRUE(saver.save((dir_ / "b.png").string(), noise(8, 4)));
  saver.flush();
  EXPECT_EQ(saver.written(), 2u);
  EXPECT_EQ(saver.dropped() + saver.failed(), 0u);
  EXPECT_GT(fs::file_size(dir_ / "a.png"), 8u * 4u);
  EXPECT_TRUE(fs::exists(dir_ / "b.png"));
  EXPECT_FALSE(fs::exists(dir_ / "a.png.part"));
}

TEST_F(FrameSaverTest, AFullQueueDropsInsteadOfGrowing) {
  const render::Image big = noise(1920, 1080);  // tens of milliseconds to encode
  FrameSaver saver;
  constexpr int kSaves = 10;  // asked for back to back, far faster than one encode
  int accepted = 0;
  for (int i = 0; i < kSaves; ++i)
    accepted += saver.save((dir_ / (std::to_string(i) + ".png")).string(), big);
  saver.flush();
  // Typically kMaxQueued + 1 (the queue, plus the one being encoded); a loaded machine may let the encoder
  // finish one between two calls, but not all of them.
  EXPECT_LT(accepted, kSaves);
  EXPECT_EQ(saver.dropped(), std::uint64_t(kSaves - accepted));
  EXPECT_EQ(saver.written(), std::uint64_t(accepted));
}

TEST_F(FrameSaverTest, WaitingForRoomLosesNothing) {
  const render::Image big = noise(640, 480);
  FrameSaver saver;
  constexpr int kSaves = 6;
  for (int i = 0; i < kSaves; ++i)
    EXPECT_TRUE(saver.save((dir_ / (std::to_string(i) + ".png")).string(), big, FrameSaver::WhenFull::Wait));
  saver.flush();
  EXPECT_EQ(saver.written(), std::uint64_t(kSaves));
  EXPECT_EQ(saver.dropped(), 0u);
}

TEST_F(FrameSaverTest, AFailedWriteIsCountedAndLeavesNoPartialFile) {
  FrameSaver saver;
  const fs::path missing = dir_ / "no-such-folder" / "frame.png";
  EXPECT_TRUE(saver.save(missing.string(), noise(4, 4)));
  EXPECT_TRUE(saver.save((dir_ / "ok.png").string(), render::Image{}));  // empty: write_png refuses it
  saver.flush();
  EXPECT_EQ(saver.failed(), 2u);
  EXPECT_EQ(saver.written(), 0u);
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_FALSE(fs::exists(dir_ / "ok.png"));
  EXPECT_FALSE(fs::exists(dir_ / "ok.png.part"));
}

}  // namespace frame_saver_test
}  // namespace walk::kiosk
