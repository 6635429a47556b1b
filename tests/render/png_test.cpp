// write_png round trip through libpng's reader, and its error for an unwritable path.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "model/error.hpp"
#include "render/renderer.hpp"

namespace walk::render {
namespace png_test {  // named, not anonymous: the suite compiles as unity batches

Image read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) throw std::runtime_error(png.message);
  png.format = PNG_FORMAT_RGBA;
  Image image;
  image.width = int(png.width);
  image.height = int(png.height);
  image.rgba.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
    throw std::runtime_error(png.message);
  return image;
}

TEST(Png, RoundTrip) {
  Image image;
  image.width = 7;  // odd sizes: no row padding may creep in
  image.height = 5;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int k = 0; k < 4; ++k) image.rgba.push_back(std::uint8_t(x * 37 + y * 11 + k * 64));
  const auto path =
      (std::filesystem::temp_directory_path() / ("walk_png_" + std::to_string(::getpid()) + ".png")).string();
  write_png(path, image);
  const Image back = read_png(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width, image.width);
  EXPECT_EQ(back.height, image.height);
  EXPECT_EQ(back.rgba, image.rgba);
}

TEST(Png, UnwritablePathNamesThePath) {
  Image image;
  image.width = image.height = 1;
  image.rgba = {1, 2, 3, 4};
  const std::string path = "/nonexistent-walk-dir/frame.png";
  try {
    write_png(path, image);
    FAIL() << "wrote to " << path;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace png_test
}  // namespace walk::render
