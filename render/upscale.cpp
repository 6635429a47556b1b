#include "render/upscale.hpp"

#include <pixman.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <memory>
#include <string>

#include "model/error.hpp"

namespace walk::render {
namespace {

struct ImageRelease {
  void operator()(pixman_image_t* image) const { pixman_image_unref(image); }
};
using PixmanImage = std::unique_ptr<pixman_image_t, ImageRelease>;

// pixman's names read the packed 32-bit word from its top byte: bytes R, G, B, A in memory are a8b8g8r8 on
// a little-endian machine and r8g8b8a8 on a big-endian one.
constexpr pixman_format_code_t kRgbaBytes =
    std::endian::native == std::endian::little ? PIXMAN_a8b8g8r8 : PIXMAN_r8g8b8a8;

std::size_t bytes_of(int width, int height) {
  return width > 0 && height > 0 ? 4 * std::size_t(width) * std::size_t(height) : 0;
}

}  // namespace

void scale_bilinear(std::span<const std::uint8_t> source, int width, int height, std::span<std::uint8_t> out,
                    int out_width, int out_height) {
  if (bytes_of(width, height) == 0 || bytes_of(out_width, out_height) == 0 ||
      source.size() != bytes_of(width, height) || out.size() != bytes_of(out_width, out_height))
    throw Error("scale_bilinear: " + std::to_string(source.size()) + " source bytes for " +
                std::to_string(width) + "x" + std::to_string(height) + " and " + std::to_string(out.size()) +
                " output bytes for " + std::to_string(out_width) + "x" + std::to_string(out_height) +
                " do not fit RGBA8 frames of those sizes");
  // Bands of rows, each with its own pixman images over the shared pixels: an image validates itself on
  // first use, so two threads must not share one.
  const std::size_t out_row = 4 * std::size_t(out_width);
  tbb::parallel_for(tbb::blocked_range<int>(0, out_height, 64), [&](const tbb::blocked_range<int>& rows) {
    // pixman takes non-const bits; the source image is only read.
    const PixmanImage from{pixman_image_create_bits(
        kRgbaBytes, width, height, reinterpret_cast<std::uint32_t*>(const_cast<std::uint8_t*>(source.data())),
        4 * width)};
    const PixmanImage to{pixman_image_create_bits(
        kRgbaBytes, out_width, int(rows.size()),
        reinterpret_cast<std::uint32_t*>(out.data() + std::size_t(rows.begin()) * out_row), 4 * out_width)};
    if (!from || !to) throw Error("scale_bilinear: pixman could not wrap the frames (out of memory)");
    // The transform maps output positions to source positions.
    pixman_transform_t to_source;
    pixman_transform_init_scale(&to_source, pixman_double_to_fixed(double(width) / double(out_width)),
                                pixman_double_to_fixed(double(height) / double(out_height)));
    pixman_image_set_transform(from.get(), &to_source);
    pixman_image_set_filter(from.get(), PIXMAN_FILTER_BILINEAR, nullptr, 0);
    pixman_image_set_repeat(from.get(), PIXMAN_REPEAT_PAD);
    // The band's first row is output row rows.begin(): the source is sampled from there on.
    pixman_image_composite32(PIXMAN_OP_SRC, from.get(), nullptr, to.get(), 0, rows.begin(), 0, 0, 0, 0,
                             out_width, int(rows.size()));
  });
}

}  // namespace walk::render
