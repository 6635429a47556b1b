// write_png through libpng's simplified API: one call, errors come back as a message.
#include <png.h>

#include <cstring>
#include <string>

#include "model/error.hpp"
#include "render/renderer.hpp"

namespace walk::render {

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * image.height * 4)
    throw Error("cannot write '" + path + "': image is empty or its pixel buffer does not match " +
                std::to_string(image.width) + "x" + std::to_string(image.height));
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.rgba.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw Error("cannot write PNG '" + path + "': " + message);
  }
}

}  // namespace walk::render
