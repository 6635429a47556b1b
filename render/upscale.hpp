#pragma once
// Scaling a frame up on the CPU: what the Reduced moving level's half-size frame becomes before it is shown.
// On a software rasteriser (llvmpipe) a GL_LINEAR blit to 1280x720 costs 5-7 ms, as much as drawing the
// half-size frame itself, because every full-size pixel is a fragment; reading the half-size frame back,
// scaling it here and uploading the result cost about 1.5 ms together. A GPU blits for free, so there the
// GL blit stays (Renderer::set_cpu_upscale).
#include <cstdint>
#include <span>

namespace walk::render {

// `source`: width x height RGBA8 pixels, rows packed; `out`: out_width x out_height the same. Bilinear with
// GL_LINEAR's sampling positions (output pixel centre x + 0.5 maps to source position (x + 0.5) * width /
// out_width, texel centres at + 0.5, the edge texel repeated past the border), by pixman, which quantises
// positions to 1/128 of a texel: at an exact double (the Reduced level at an even frame size) within 1 in a
// channel of the exact filter and of llvmpipe's blit; at other ratios within 2 of the blit on a rendered
// frame (up to 4 at a full-range edge). Bands of rows are scaled on TBB's threads. Throws walk::Error when
// the sizes do not match.
void scale_bilinear(std::span<const std::uint8_t> source, int width, int height, std::span<std::uint8_t> out,
                    int out_width, int out_height);

}  // namespace walk::render
