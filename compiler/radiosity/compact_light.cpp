#include "compiler/radiosity/compact_light.hpp"

#include <algorithm>
#include <cmath>

#include "model/compact_code.hpp"

namespace walk::compiler {
namespace {

double luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// What a display shows of circuit c at vertex v from the compact form with `code`, channel by channel.
void compact_value(const CompactLight& compact, std::size_t v, std::size_t c, std::uint8_t code,
                   float out[3]) {
  const double i = compact.scale[c] * model::compact_intensity(code);
  for (int ch = 0; ch < 3; ++ch) out[ch] = static_cast<float>(compact.colour[v][ch] / 255.0 * i);
}

// Relative L2 error: RMS of shown - exact over every vertex and channel, in units of the exact light's RMS;
// of each circuit alone (`per_circuit`) and of all circuits on (returned). A circuit lighting one room of
// many is measured where it lights, not diluted (or inflated) by the dark vertices of the others' rooms, as
// a mean would. Shown: every circuit from the compact form if `all_compact`, else as `compact` chooses.
// One pass over the light's entries (a circuit that does not reach a vertex codes 0 there: shown 0, exact),
// nothing the size of the light allocated.
double relative_rms(const CompactLight& compact, bool all_compact, const model::LightRowsView& light,
                    std::size_t circuits, std::span<const std::uint8_t> glowing,
                    std::vector<double>& per_circuit) {
  std::vector<double> error(circuits, 0.0), norm(circuits, 0.0);
  double all_error = 0.0, all_norm = 0.0;
  for (std::size_t v = 0; v < light.rows(); ++v) {
    if (!glowing.empty() && glowing[v]) continue;
    double x[3] = {0.0, 0.0, 0.0}, y[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = light.first[v]; i < light.first[v + 1]; ++i) {
      const model::LightEntry& e = light.entries[i];
      const std::size_t c = e.circuit;
      const float* exact = e.rgb;
      float shown[3] = {exact[0], exact[1], exact[2]};
      if (all_compact || compact.compact[c]) compact_value(compact, v, c, compact.entry_code[i], shown);
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

CompactLight compact_light(const model::LightRowsView& light, std::size_t vertices, std::size_t circuits,
                           std::span<const std::uint8_t> included, std::span<const std::uint8_t> glowing) {
  CompactLight out;
  out.colour.resize(vertices, {0, 0, 0, 255});
  out.entry_code.assign(light.entries.size(), 0);
  out.scale.assign(circuits, 0.0f);
  out.compact.assign(circuits, 1);
  if (!included.empty())
    for (std::size_t c = 0; c < circuits; ++c) out.compact[c] = included[c] ? 1 : 0;
  const std::size_t rows = std::min(vertices, light.rows());
  std::vector<double> colour_lum(vertices, 0.0);
  for (std::size_t v = 0; v < rows; ++v) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (const model::LightEntry& e : light.row(v))
      if (out.compact[e.circuit])
        for (int ch = 0; ch < 3; ++ch) sum[ch] += e.rgb[ch];
    const double peak = std::max({sum[0], sum[1], sum[2]});
    if (peak <= 0.0) continue;
    for (int ch = 0; ch < 3; ++ch)
      out.colour[v][ch] = static_cast<std::uint8_t>(std::lround(255.0 * sum[ch] / peak));
    colour_lum[v] = luminance(out.colour[v][0] / 255.0, out.colour[v][1] / 255.0, out.colour[v][2] / 255.0);
  }
  // Every circuit is coded against the colour, those left out too: their error is the reason they are out.
  // Two passes over the entries: each circuit's scale (its largest luminance relative to the colour's), then
  // the codes.
  auto relative = [&](std::size_t v, const model::LightEntry& e) {
    return colour_lum[v] > 0.0 ? luminance(e.rgb[0], e.rgb[1], e.rgb[2]) / colour_lum[v] : 0.0;
  };
  for (std::size_t v = 0; v < rows; ++v)
    for (const model::LightEntry& e : light.row(v))
      out.scale[e.circuit] = std::max(out.scale[e.circuit], static_cast<float>(relative(v, e)));
  for (std::size_t v = 0; v < rows; ++v)
    for (std::size_t i = light.first[v]; i < light.first[v + 1]; ++i) {
      const model::LightEntry& e = light.entries[i];
      if (out.scale[e.circuit] > 0.0f)
        out.entry_code[i] = model::compact_code(relative(v, e) / out.scale[e.circuit]);
    }
  relative_rms(out, true, light, circuits, glowing, out.circuit_rms);
  for (std::size_t c = 0; c < circuits; ++c) {
    if (out.compact[c]) {
      out.worst_circuit_rms = std::max(out.worst_circuit_rms, out.circuit_rms[c]);
      continue;
    }
    out.scale[c] = 0.0f;
  }
  // LINT: the codes of the circuits shown compact, a row per vertex.
  for (std::size_t v = 0; v < vertices; ++v) {
    for (std::size_t i = v < rows ? light.first[v] : 0; v < rows && i < light.first[v + 1]; ++i) {
      const std::uint32_t c = light.entries[i].circuit;
      if (out.compact[c]) out.intensity.add(c, out.entry_code[i]);
    }
    out.intensity.end_row();
  }
  std::vector<double> unused;
  out.rms_error_all_on = relative_rms(out, false, light, circuits, glowing, unused);
  return out;
}

CompactLight choose_light_forms(const model::LightRowsView& light, std::size_t vertices, std::size_t circuits,
                                std::span<const std::uint8_t> glowing, double limit) {
  // Greedy, worst first: the worst circuit's tint is what pulls the shared colour away from the others.
  // Each pass costs O(light entries); after this many the rest above the limit go out together.
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

std::vector<float> expand_compact(const CompactLight& compact, const model::LightRowsView& light,
                                  std::size_t vertices, std::size_t circuits) {
  std::vector<float> out = light.dense(circuits);
  out.resize(vertices * circuits * 3, 0.0f);
  // A compact circuit shows its code, 0 where it has none.
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t c = 0; c < circuits; ++c)
      if (compact.compact.empty() || compact.compact[c]) std::fill_n(&out[(v * circuits + c) * 3], 3, 0.0f);
  for (std::size_t v = 0; v < compact.intensity.rows(); ++v)
    for (const std::uint32_t e : compact.intensity.row(v)) {
      const std::uint32_t c = model::code_circuit(e);
      compact_value(compact, v, c, model::code_value(e), &out[(v * circuits + c) * 3]);
    }
  return out;
}

}  // namespace walk::compiler
