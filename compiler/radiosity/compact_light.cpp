#include "compiler/radiosity/compact_light.hpp"

#include <algorithm>
#include <cmath>

namespace walk::compiler {
namespace {

double luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

double rms_relative(std::span<const float> a, std::span<const float> b, std::size_t vertices,
                    std::size_t circuits, std::size_t only_circuit, bool all_on) {
  double sq = 0.0, sum = 0.0;
  std::size_t n = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    for (int ch = 0; ch < 3; ++ch) {
      double x = 0.0, y = 0.0;
      for (std::size_t c = 0; c < circuits; ++c) {
        if (!all_on && c != only_circuit) continue;
        x += a[(v * circuits + c) * 3 + ch];
        y += b[(v * circuits + c) * 3 + ch];
      }
      sq += (x - y) * (x - y);
      sum += y;
      ++n;
    }
  }
  return sum > 0.0 ? std::sqrt(sq / n) / (sum / n) : 0.0;
}

}  // namespace

CompactLight compact_light(std::span<const float> light, std::size_t vertices, std::size_t circuits) {
  CompactLight out;
  out.colour.resize(vertices, {0, 0, 0, 255});
  out.intensity.assign(vertices * circuits, 0);
  out.scale.assign(circuits, 0.0f);
  std::vector<double> relative(vertices * circuits, 0.0);  // luminance of circuit c over that of the colour
  for (std::size_t v = 0; v < vertices; ++v) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < circuits; ++c)
      for (int ch = 0; ch < 3; ++ch) sum[ch] += light[(v * circuits + c) * 3 + ch];
    const double peak = std::max({sum[0], sum[1], sum[2]});
    if (peak <= 0.0) continue;
    for (int ch = 0; ch < 3; ++ch)
      out.colour[v][ch] = static_cast<std::uint8_t>(std::lround(255.0 * sum[ch] / peak));
    const double colour_lum =
        luminance(out.colour[v][0] / 255.0, out.colour[v][1] / 255.0, out.colour[v][2] / 255.0);
    if (colour_lum <= 0.0) continue;
    for (std::size_t c = 0; c < circuits; ++c) {
      const float* b = &light[(v * circuits + c) * 3];
      relative[v * circuits + c] = luminance(b[0], b[1], b[2]) / colour_lum;
      out.scale[c] = std::max(out.scale[c], static_cast<float>(relative[v * circuits + c]));
    }
  }
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t c = 0; c < circuits; ++c)
      if (out.scale[c] > 0.0f)
        out.intensity[v * circuits + c] = static_cast<std::uint8_t>(
            std::lround(255.0 * std::sqrt(std::clamp(relative[v * circuits + c] / out.scale[c], 0.0, 1.0))));
  const std::vector<float> back = expand_compact(out, vertices, circuits);
  out.rms_error_all_on = rms_relative(back, light, vertices, circuits, 0, true);
  for (std::size_t c = 0; c < circuits; ++c)
    out.worst_circuit_rms =
        std::max(out.worst_circuit_rms, rms_relative(back, light, vertices, circuits, c, false));
  return out;
}

std::vector<float> expand_compact(const CompactLight& compact, std::size_t vertices, std::size_t circuits) {
  std::vector<float> out(vertices * circuits * 3, 0.0f);
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t c = 0; c < circuits; ++c) {
      const double q = compact.intensity[v * circuits + c] / 255.0;
      const double i = compact.scale[c] * q * q;
      for (int ch = 0; ch < 3; ++ch)
        out[(v * circuits + c) * 3 + ch] = static_cast<float>(compact.colour[v][ch] / 255.0 * i);
    }
  return out;
}

}  // namespace walk::compiler
