#pragma once
// Albedo maps read for the compiler: PNG (libpng) and JPEG (libjpeg-turbo), from a file or from bytes a
// model embeds (glTF). Texels come out as model::Texture: 8-bit sRGB RGBA, rows bottom-up, at most
// kMaxTextureSide on a side (halved by a box filter in linear light until they fit), with the mean texel in
// linear light taken at the file's full resolution.
#include <cstdint>
#include <span>
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

// Longest side a bundle stores: 1024 texels of a 2 m tile is 2 mm each, below what a kiosk frame resolves,
// and keeps a texture at 4 MiB (5.3 MiB with the mipmaps the renderer builds).
inline constexpr std::uint32_t kMaxTextureSide = 1024;

// Throws walk::Error naming `path` when the file cannot be read or is not a PNG or JPEG it can decode.
[[nodiscard]] model::Texture load_texture(const std::string& path);

// `bytes` is a whole PNG or JPEG file; `where` names it in errors (the model file and the texture's name).
[[nodiscard]] model::Texture decode_texture(std::span<const std::uint8_t> bytes, const std::string& where);

// Texels already decoded (an embedded glTF texture assimp leaves raw), 8-bit sRGB RGBA rows top-down.
[[nodiscard]] model::Texture texture_from_rgba(std::vector<std::uint8_t> rgba_top_down, std::uint32_t width,
                                               std::uint32_t height);

}  // namespace walk::compiler
