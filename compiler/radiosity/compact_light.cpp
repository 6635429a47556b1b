#include "compiler/radiosity/compact_light.hpp"

#include <algorithm>
#include <cmath>

#include "model/compact_code.hpp"

namespace walk::compiler {
namespace {

double luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// What a display shows of circuit c at vertex v from the compact form, channel by channel.
void compact_value(const CompactLight& compact, std::size_t v, std::size_t c, std::size_t circuits,
                   float out[3]) {
  const double i = compact.scale[c] * model::compact_intensity(compact.intensity[v * circuits + c]);
  for (int ch = 0; ch < 3; ++ch) out[ch] = static_cast<float>(compact.colour[v][ch] / 255.0 * i);
}

// Relative L2 error: RMS of shown - exact over every vertex and channel, in units of the exact light's RMS;
// of each circuit alone (`per_circuit`) and of all circuits on (returned). A circuit lighting one room of
// many is measured where it lights, not diluted (or inflated) by the dark vertices of the others' rooms, as
// a mean would. Shown: every circuit from the compact form if `all_compact`, else as `compact` chooses.
// One pass, O(vertices x circuits), nothing the size of the light allocated.
double relative_rms(const CompactLight& compact, bool all_compact, std::span<const float> light,
                    std::size_t vertices, std::size_t circuits, std::span<const std::uint8_t> glowing,
                    std::vector<double>& per_circuit) {
  std::vector<double> error(circuits, 0.0), norm(circuits, 0.0);
  double all_error = 0.0, all_norm = 0.0;
  for (std::size_t v = 0; v < vertices; ++v) {
    if (!glowing.empty() && glowing[v]) continue;
    double x[3] = {0.0, 0.0, 0.0}, y[3] = {0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < circuits; ++c) {
      const float* exact = &light[(v * circuits + c) * 3];
      float shown[3] = {exact[0], exact[1], exact[2]};
      if (all_compact || compact.compact[c]) compact_value(compact, v, c, circuits, shown);
      for (int ch = 0; ch < 3; ++ch) {
        const double d = double(shown[ch]) - exact[ch];
        error[c] += d * d;
        norm[c] += double(exact[ch]) * exact[ch];
        x[ch] += shown[ch];
        y[ch] += exact[ch];
      }
    }
    for (int ch = 0; ch < 3; ++ch) {
      all_error += (x[ch] - y[ch]) * (x[ch] - y[ch]);
      all_norm += y[ch] * y[ch];
    }
  }
  per_circuit.assign(circuits, 0.0);
  for (std::size_t c = 0; c < circuits; ++c)
    per_circuit[c] = norm[c] > 0.0 ? std::sqrt(error[c] / norm[c]) : 0.0;
  return all_norm > 0.0 ? std::sqrt(all_error / all_norm) : 0.0;
}

}  // namespace

CompactLight compact_light(std::span<const float> light, std::size_t vertices, std::size_t circuits,
                           std::span<const std::uint8_t> included, std::span<const std::uint8_t> glowing) {
  CompactLight out;
  out.colour.resize(vertices, {0, 0, 0, 255});
  out.intensity.assign(vertices * circuits, 0);
  out.scale.assign(circuits, 0.0f);
  out.compact.assign(circuits, 1);
  if (!included.empty())
    for (std::size_t c = 0; c < circuits; ++c) out.compact[c] = included[c] ? 1 : 0;
  std::vector<double> colour_lum(vertices, 0.0);
  for (std::size_t v = 0; v < vertices; ++v) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < circuits; ++c)
      if (out.compact[c])
        for (int ch = 0; ch < 3; ++ch) sum[ch] += light[(v * circuits + c) * 3 + ch];
    const double peak = std::max({sum[0], sum[1], sum[2]});
    if (peak <= 0.0) continue;
    for (int ch = 0; ch < 3; ++ch)
      out.colour[v][ch] = static_cast<std::uint8_t>(std::lround(255.0 * sum[ch] / peak));
    colour_lum[v] = luminance(out.colour[v][0] / 255.0, out.colour[v][1] / 255.0, out.colour[v][2] / 255.0);
  }
  // Every circuit is coded against the colour, those left out too: their error is the reason they are out.
  std::vector<double> relative(vertices);  // luminance of the circuit over that of the colour
  for (std::size_t c = 0; c < circuits; ++c) {
    for (std::size_t v = 0; v < vertices; ++v) {
      const float* b = &light[(v * circuits + c) * 3];
      relative[v] = colour_lum[v] > 0.0 ? luminance(b[0], b[1], b[2]) / colour_lum[v] : 0.0;
      out.scale[c] = std::max(out.scale[c], static_cast<float>(relative[v]));
    }
    if (out.scale[c] > 0.0f)
      for (std::size_t v = 0; v < vertices; ++v)
        out.intensity[v * circuits + c] = model::compact_code(relative[v] / out.scale[c]);
  }
  relative_rms(out, true, light, vertices, circuits, glowing, out.circuit_rms);
  for (std::size_t c = 0; c < circuits; ++c) {
    if (out.compact[c]) {
      out.worst_circuit_rms = std::max(out.worst_circuit_rms, out.circuit_rms[c]);
      continue;
    }
    out.scale[c] = 0.0f;
    for (std::size_t v = 0; v < vertices; ++v) out.intensity[v * circuits + c] = 0;
  }
  std::vector<double> unused;
  out.rms_error_all_on = relative_rms(out, false, light, vertices, circuits, glowing, unused);
  return out;
}

CompactLight choose_light_forms(std::span<const float> light, std::size_t vertices, std::size_t circuits,
                                std::span<const std::uint8_t> glowing, double limit) {
  // Greedy, worst first: the worst circuit's tint is what pulls the shared colour away from the others.
  // Each pass costs O(vertices x circuits); after this many the rest above the limit go out together.
  constexpr int kWorstFirstPasses = 16;
  std::vector<std::uint8_t> included(circuits, 1);
  std::vector<double> ruled_out_at(circuits, 0.0);  // a circuit's error when it was left out
  for (int pass = 0;; ++pass) {
    CompactLight c = compact_light(light, vertices, circuits, included, glowing);
    std::size_t worst = circuits;
    for (std::size_t i = 0; i < circuits; ++i)
      if (included[i] && c.circuit_rms[i] > limit &&
          (worst == circuits || c.circuit_rms[i] > c.circuit_rms[worst]))
        worst = i;
    if (worst == circuits) {
      for (std::size_t i = 0; i < circuits; ++i)
        if (!included[i]) c.circuit_rms[i] = ruled_out_at[i];
      return c;
    }
    for (std::size_t i = 0; i < circuits; ++i)
      if (included[i] && (i == worst || (pass >= kWorstFirstPasses && c.circuit_rms[i] > limit))) {
        included[i] = 0;
        ruled_out_at[i] = c.circuit_rms[i];
      }
  }
}

std::vector<float> expand_compact(const CompactLight& compact, std::span<const float> light,
                                  std::size_t vertices, std::size_t circuits) {
  std::vector<float> out(light.begin(), light.begin() + std::ptrdiff_t(vertices * circuits * 3));
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t c = 0; c < circuits; ++c)
      if (compact.compact.empty() || compact.compact[c])
        compact_value(compact, v, c, circuits, &out[(v * circuits + c) * 3]);
  return out;
}

}  // namespace walk::compiler
