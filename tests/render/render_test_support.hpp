#pragma once
// Shared by the pixel tests: a backend of each headless kind, and a frame rendered through it.
#include <memory>
#include <string>

#include "render/backend/backend.hpp"
#include "render/renderer.hpp"

namespace walk::render::test {

inline constexpr int kWidth = 160;
inline constexpr int kHeight = 120;

[[nodiscard]] std::unique_ptr<Backend> headless(BackendKind kind, int width = kWidth, int height = kHeight);

// Eye in the middle of room A at 1.5 m, looking along +x (through the opening) or -x (at A's outer wall).
[[nodiscard]] View looking_along_x(double sign, double eye_x = 2.0);

// The pixel at the centre of the image.
[[nodiscard]] const std::uint8_t* centre(const Image& image);

}  // namespace walk::render::test
