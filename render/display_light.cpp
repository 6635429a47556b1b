#include "render/display_light.hpp"

#include "model/compact_code.hpp"

namespace walk::render {

DisplayLight::DisplayLight(const model::Bundle& bundle, DisplayLightForm form) : bundle_(bundle) {
  const auto circuits = bundle.circuits();
  const bool has_compact = !bundle.compact_intensity().empty();
  std::vector<char> compact(circuits.size(), 0);
  for (std::uint32_t c = 0; c < circuits.size(); ++c) {
    compact[c] = form == DisplayLightForm::AsCompiled && has_compact &&
                 circuits[c].light_form == model::LightForm::Compact;
    (compact[c] ? compact_ : full_).push_back(c);
  }
  const std::size_t n = circuits.size(), vertices = bundle.vertices().size();
  const auto light = bundle.light();
  const auto codes = bundle.compact_intensity();
  ranges_.resize(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    VertexLightRange& range = ranges_[v];
    const std::size_t full_first = full_entries_.size(), compact_first = compact_entries_.size();
    for (const std::uint32_t c : full_) {
      const float* l = &light[(v * n + c) * 3];
      if (l[0] != 0.0f || l[1] != 0.0f || l[2] != 0.0f)
        full_entries_.push_back({{l[0], l[1], l[2]}, float(c)});
    }
    for (const std::uint32_t c : compact_)
      if (const std::uint8_t code = codes[v * n + c]; code != 0) compact_entries_.push_back(c << 8 | code);
    if (full_entries_.size() > full_first) {
      range.full_first = std::uint32_t(full_first);
      full_entries_.back().circuit += kLastFullEntry;
    }
    if (compact_entries_.size() > compact_first) {
      range.compact_first = std::uint32_t(compact_first);
      compact_entries_.back() |= kLastCompactEntry;
    }
  }
}

void DisplayLight::shader_levels(std::span<const float> levels, std::vector<float>& out) const {
  out.assign(levels.begin(), levels.end());
  for (const std::uint32_t c : compact_) out[c] = levels[c] * bundle_.circuits()[c].compact_scale;
}

glm::vec3 DisplayLight::mixed(std::size_t vertex, std::span<const float> levels) const {
  const VertexLightRange& range = ranges_[vertex];
  glm::vec3 sum(0.0f);
  for (std::uint32_t i = range.full_first; i != VertexLightRange::kNone; ++i) {
    const FullLightEntry& e = full_entries_[i];
    const bool last = e.circuit >= kLastFullEntry;
    sum += levels[std::size_t(last ? e.circuit - kLastFullEntry : e.circuit)] *
           glm::vec3(e.rgb[0], e.rgb[1], e.rgb[2]);
    if (last) break;
  }
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

std::size_t DisplayLight::gpu_bytes() const {
  return ranges_.size() * sizeof(VertexLightRange) + full_entries_.size() * sizeof(FullLightEntry) +
         compact_entries_.size() * sizeof(CompactLightEntry) +
         (compact_.empty() ? 0 : bundle_.compact_colour().size_bytes());
}

std::size_t DisplayLight::full_form_bytes() const {
  return bundle_.light().size_bytes();
}

}  // namespace walk::render
