#include "compiler/import/texture_image.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared before it
#include <cstring>
#include <fstream>
#include <iterator>
// clang-format off
#include <jpeglib.h>
// clang-format on

#include "model/error.hpp"
#include "model/srgb.hpp"

namespace walk::compiler {
namespace {

// One halving step of a side longer than kMaxTextureSide: each texel the mean of up to 2x2 in linear light
// (alpha averaged as it is).
void halve(model::Texture& t) {
  const auto& lin = model::srgb_decode_table();
  const std::uint32_t w = std::max(1u, t.width / 2), h = std::max(1u, t.height / 2);
  const std::uint32_t sx = t.width > 1 ? 2 : 1, sy = t.height > 1 ? 2 : 1;
  std::vector<std::uint8_t> out(std::size_t(w) * h * 4);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      double sum[4] = {0, 0, 0, 0};
      for (std::uint32_t dy = 0; dy < sy; ++dy)
        for (std::uint32_t dx = 0; dx < sx; ++dx) {
          const std::uint8_t* p = &t.rgba[(std::size_t(y * sy + dy) * t.width + x * sx + dx) * 4];
          for (int c = 0; c < 3; ++c) sum[c] += lin[p[c]];
          sum[3] += p[3];
        }
      const double n = double(sx * sy);
      std::uint8_t* o = &out[(std::size_t(y) * w + x) * 4];
      for (int c = 0; c < 3; ++c) o[c] = model::srgb_encode_byte(sum[c] / n);
      o[3] = static_cast<std::uint8_t>(std::lround(sum[3] / n));
    }
  t.rgba = std::move(out);
  t.width = w;
  t.height = h;
}

std::vector<std::uint8_t> decode_png(std::span<const std::uint8_t> bytes, const std::string& where,
                                     std::uint32_t& width, std::uint32_t& height) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
    throw Error(where + ": not a readable PNG (" + png.message + "); re-export the texture");
  png.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, rgba.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw Error(where + ": PNG is damaged (" + message + "); re-export the texture");
  }
  width = png.width;
  height = png.height;
  return rgba;
}

struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpeg_fail(j_common_ptr info) {
  auto* e = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, e->message);
  std::longjmp(e->jump, 1);
}

// libjpeg reports errors by longjmp; no C++ object with a destructor is created between setjmp and the
// last libjpeg call, so none is skipped.
std::vector<std::uint8_t> decode_jpeg(std::span<const std::uint8_t> bytes, const std::string& where,
                                      std::uint32_t& width, std::uint32_t& height) {
  std::vector<std::uint8_t> rgba;
  jpeg_decompress_struct info{};
  JpegError error{};
  info.err = jpeg_std_error(&error.mgr);
  error.mgr.error_exit = jpeg_fail;
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&info);
    throw Error(where + ": JPEG is damaged (" + error.message + "); re-export the texture");
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_EXT_RGBA;  // libjpeg-turbo: grey and CMYK converted too
  jpeg_start_decompress(&info);
  width = info.output_width;
  height = info.output_height;
  rgba.resize(std::size_t(width) * height * 4);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = &rgba[std::size_t(info.output_scanline) * width * 4];
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return rgba;
}

}  // namespace

model::Texture texture_from_rgba(std::vector<std::uint8_t> rgba, std::uint32_t width, std::uint32_t height) {
  model::Texture t;
  t.width = width;
  t.height = height;
  // Bottom row first, as GL's t = 0 (OBJ's and assimp's v = 0) is the image's bottom.
  const std::size_t row = std::size_t(width) * 4;
  for (std::uint32_t y = 0; y < height / 2; ++y)
    std::swap_ranges(rgba.begin() + std::ptrdiff_t(y * row), rgba.begin() + std::ptrdiff_t((y + 1) * row),
                     rgba.begin() + std::ptrdiff_t((height - 1 - y) * row));
  t.rgba = std::move(rgba);
  const auto& lin = model::srgb_decode_table();
  model::Rgb sum(0.0);
  for (std::size_t i = 0; i + 3 < t.rgba.size(); i += 4)
    sum += model::Rgb(lin[t.rgba[i]], lin[t.rgba[i + 1]], lin[t.rgba[i + 2]]);
  t.mean = width && height ? sum / double(std::size_t(width) * height) : model::Rgb(1.0);
  while (t.width > kMaxTextureSide || t.height > kMaxTextureSide) halve(t);
  return t;
}

model::Texture decode_texture(std::span<const std::uint8_t> bytes, const std::string& where) {
  static constexpr std::uint8_t kPng[] = {0x89, 'P', 'N', 'G'};
  static constexpr std::uint8_t kJpeg[] = {0xFF, 0xD8, 0xFF};
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  if (bytes.size() >= 4 && std::equal(std::begin(kPng), std::end(kPng), bytes.begin()))
    rgba = decode_png(bytes, where, width, height);
  else if (bytes.size() >= 3 && std::equal(std::begin(kJpeg), std::end(kJpeg), bytes.begin()))
    rgba = decode_jpeg(bytes, where, width, height);
  else
    throw Error(where + ": neither PNG nor JPEG; convert the texture to one of them");
  if (width == 0 || height == 0) throw Error(where + ": the image has no texels; re-export the texture");
  return texture_from_rgba(std::move(rgba), width, height);
}

model::Texture load_texture(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(located(path, 0, "cannot open the texture", "check that it exists and is readable"));
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  return decode_texture(bytes, path);
}

}  // namespace walk::compiler
