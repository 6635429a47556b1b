#include "render/display_light.hpp"

#include <algorithm>

#include "model/compact_code.hpp"

namespace walk::render {

namespace {

// Appends the entries of `row` whose circuit `shown` marks, marking the last; returns the first entry, or
// kNone when none is shown there.
std::uint32_t append_lit(std::span<const model::LightEntry> row, const std::vector<char>& shown,
                         std::vector<FullLightEntry>& entries) {
  const std::size_t first = entries.size();
  for (const model::LightEntry& e : row)
    if (shown[e.circuit]) entries.push_back({{e.rgb[0], e.rgb[1], e.rgb[2]}, float(e.circuit)});
  if (entries.size() == first) return VertexLightRange::kNone;
  entries.back().circuit += kLastFullEntry;
  return std::uint32_t(first);
}

// Level x radiosity summed over the run of entries from `first` (kNone: none), as the vertex shader does.
glm::vec3 sum_lit(const std::vector<FullLightEntry>& entries, std::uint32_t first,
                  std::span<const float> levels) {
  glm::vec3 sum(0.0f);
  for (std::uint32_t i = first; i != VertexLightRange::kNone; ++i) {
    const FullLightEntry& e = entries[i];
    const bool last = e.circuit >= kLastFullEntry;
    sum += levels[std::size_t(last ? e.circuit - kLastFullEntry : e.circuit)] *
           glm::vec3(e.rgb[0], e.rgb[1], e.rgb[2]);
    if (last) break;
  }
  return sum;
}

// Where the bundle lacks PLGT: each polygon's plain mean of its vertices' light, so the coarse level always
// exists.
model::LightRows mean_vertex_light(const model::Bundle& bundle) {
  model::LightRows out;
  const auto light = bundle.light();
  std::vector<float> sum(bundle.circuits().size() * 3, 0.0f);
  std::vector<std::uint32_t> touched;
  for (const auto& poly : bundle.polygons()) {
    for (std::uint32_t v = poly.first_vertex; !light.empty() && v < poly.first_vertex + poly.vertex_count;
         ++v)
      for (const model::LightEntry& e : light.row(v)) {
        if (sum[e.circuit * 3] == 0.0f && sum[e.circuit * 3 + 1] == 0.0f && sum[e.circuit * 3 + 2] == 0.0f)
          touched.push_back(e.circuit);
        for (int c = 0; c < 3; ++c) sum[e.circuit * 3 + c] += e.rgb[c];
      }
    std::sort(touched.begin(), touched.end());
    for (const std::uint32_t c : touched) {
      float mean[3];
      for (int k = 0; k < 3; ++k) {
        mean[k] = sum[c * 3 + k] / float(poly.vertex_count);
        sum[c * 3 + k] = 0.0f;
      }
      out.add(c, mean);
    }
    touched.clear();
    out.end_row();
  }
  return out;
}

}  // namespace

DisplayLight::DisplayLight(const model::Bundle& bundle, DisplayLightForm form) : bundle_(bundle) {
  const auto circuits = bundle.circuits();
  const bool has_compact = !bundle.compact_intensity().empty() && !bundle.compact_colour().empty();
  for (std::uint32_t c = 0; c < circuits.size(); ++c) {
    const bool compact = form == DisplayLightForm::AsCompiled && has_compact &&
                         circuits[c].light_form == model::LightForm::Compact;
    (compact ? compact_ : full_).push_back(c);
  }
  const std::size_t n = circuits.size(), vertices = bundle.vertices().size();
  const auto light = bundle.light();
  const auto codes = bundle.compact_intensity();
  std::vector<char> shown_full(n, 0);
  for (const std::uint32_t c : full_) shown_full[c] = 1;
  ranges_.resize(vertices);
  for (std::size_t v = 0; v < vertices && !light.empty(); ++v) {
    VertexLightRange& range = ranges_[v];
    range.full_first = append_lit(light.row(v), shown_full, full_entries_);
    const std::size_t compact_first = compact_entries_.size();
    if (!compact_.empty())
      for (const std::uint32_t e : codes.row(v))  // LINT holds the circuits shown compact only
        compact_entries_.push_back(e);
    if (compact_entries_.size() > compact_first) {
      range.compact_first = std::uint32_t(compact_first);
      compact_entries_.back() |= kLastCompactEntry;
    }
  }
  // The coarse level's light has every circuit as floats, compact ones included.
  const std::vector<char> every(n, 1);
  model::LightRows means;
  const model::LightRowsView rows = bundle.polygon_light().rows() == bundle.polygons().size()
                                        ? bundle.polygon_light()
                                        : (means = mean_vertex_light(bundle)).view();
  polygon_first_.resize(bundle.polygons().size());
  for (std::size_t p = 0; p < polygon_first_.size(); ++p)
    polygon_first_[p] = append_lit(rows.row(p), every, polygon_entries_);
  // The shader's level of a compact circuit is level x scale (shader_levels): its polygon light is stored
  // divided by the scale, which is positive wherever the circuit has light.
  std::vector<float> divisor(n, 1.0f);
  for (const std::uint32_t c : compact_)
    if (circuits[c].compact_scale > 0.0f) divisor[c] = circuits[c].compact_scale;
  for (FullLightEntry& e : polygon_entries_) {
    const float c = e.circuit >= kLastFullEntry ? e.circuit - kLastFullEntry : e.circuit;
    for (float& x : e.rgb) x /= divisor[std::size_t(c)];
  }
}

void DisplayLight::shader_levels(std::span<const float> levels, std::vector<float>& out) const {
  out.assign(levels.begin(), levels.end());
  for (const std::uint32_t c : compact_) out[c] = levels[c] * bundle_.circuits()[c].compact_scale;
}

glm::vec3 DisplayLight::mixed(std::size_t vertex, std::span<const float> levels) const {
  const VertexLightRange& range = ranges_[vertex];
  const glm::vec3 sum = sum_lit(full_entries_, range.full_first, levels);
  if (compact_.empty()) return sum;
  float intensity = 0.0f;
  for (std::uint32_t i = range.compact_first; i != VertexLightRange::kNone; ++i) {
    const std::uint32_t e = compact_entries_[i];
    const std::uint32_t c = (e & ~kLastCompactEntry) >> 8;
    intensity += levels[c] * bundle_.circuits()[c].compact_scale * float(model::compact_intensity(e & 0xffu));
    if (e & kLastCompactEntry) break;
  }
  const auto& colour = bundle_.compact_colour()[vertex];
  return sum + intensity * glm::vec3(colour[0], colour[1], colour[2]) / 255.0f;
}

glm::vec3 DisplayLight::polygon_mixed(std::size_t polygon, std::span<const float> levels) const {
  std::vector<float> shader;
  shader_levels(levels, shader);
  return sum_lit(polygon_entries_, polygon_first_[polygon], shader);
}

std::size_t DisplayLight::gpu_bytes() const {
  return ranges_.size() * sizeof(VertexLightRange) + full_entries_.size() * sizeof(FullLightEntry) +
         compact_entries_.size() * sizeof(CompactLightEntry) +
         (compact_.empty() ? 0 : bundle_.compact_colour().size_bytes());
}

std::size_t DisplayLight::full_form_bytes() const {
  return bundle_.light().first.size_bytes() + bundle_.light().entries.size_bytes();
}

}  // namespace walk::render
