#pragma once
// Texture images written for the tests: PNGs through libpng, texels given top row first as files hold them.
#include <png.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace walk::compiler::test {

inline void write_test_png(const std::string& path, std::uint32_t width, std::uint32_t height,
                           const std::vector<std::uint8_t>& rgba_top_down) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = width;
  png.height = height;
  png.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_file(&png, path.c_str(), 0, rgba_top_down.data(), 0, nullptr))
    throw std::runtime_error("cannot write test PNG " + path + ": " + png.message);
}

// A `cells` x `cells` checkerboard of `side` texels, `dark` and `bright` grey (sRGB bytes); black and
// white by default, whose mean in linear light is 0.5 exactly.
inline std::vector<std::uint8_t> checkerboard(std::uint32_t side, std::uint32_t cells, std::uint8_t dark = 0,
                                              std::uint8_t bright = 255) {
  std::vector<std::uint8_t> rgba(std::size_t(side) * side * 4);
  for (std::uint32_t y = 0; y < side; ++y)
    for (std::uint32_t x = 0; x < side; ++x) {
      const bool white = ((x * cells / side) + (y * cells / side)) % 2 == 0;
      std::uint8_t* p = &rgba[(std::size_t(y) * side + x) * 4];
      p[0] = p[1] = p[2] = white ? bright : dark;
      p[3] = 255;
    }
  return rgba;
}

}  // namespace walk::compiler::test
