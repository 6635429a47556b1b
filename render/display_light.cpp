#include "render/display_light.hpp"

#include "model/compact_code.hpp"

namespace walk::render {

DisplayLight::DisplayLight(const model::Bundle& bundle, DisplayLightForm form) : bundle_(bundle) {
  const auto circuits = bundle.circuits();
  const bool has_compact = !bundle.compact_intensity().empty();
  for (std::uint32_t c = 0; c < circuits.size(); ++c) {
    const bool compact = form == DisplayLightForm::AsCompiled && has_compact &&
                         circuits[c].light_form == model::LightForm::Compact;
    (compact ? compact_ : full_).push_back(c);
  }
}

std::span<const float> DisplayLight::full_light(std::vector<float>& packed) const {
  const std::size_t circuits = bundle_.circuits().size();
  if (full_.size() == circuits) return bundle_.light();
  const auto light = bundle_.light();
  const std::size_t vertices = bundle_.vertices().size();
  packed.resize(vertices * full_.size() * 3);
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t i = 0; i < full_.size(); ++i)
      for (int ch = 0; ch < 3; ++ch)
        packed[(v * full_.size() + i) * 3 + ch] = light[(v * circuits + full_[i]) * 3 + ch];
  return packed;
}

std::vector<std::uint8_t> DisplayLight::compact_codes() const {
  if (compact_.empty()) return {};
  const auto codes = bundle_.compact_intensity();
  const std::size_t circuits = bundle_.circuits().size(), vertices = bundle_.vertices().size();
  std::vector<std::uint8_t> out(vertices * compact_.size());
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::size_t j = 0; j < compact_.size(); ++j)
      out[v * compact_.size() + j] = codes[v * circuits + compact_[j]];
  return out;
}

void DisplayLight::split_levels(std::span<const float> levels, std::vector<float>& full,
                                std::vector<float>& compact) const {
  full.resize(full_.size());
  compact.resize(compact_.size());
  for (std::size_t i = 0; i < full_.size(); ++i) full[i] = levels[full_[i]];
  for (std::size_t j = 0; j < compact_.size(); ++j)
    compact[j] = levels[compact_[j]] * bundle_.circuits()[compact_[j]].compact_scale;
}

glm::vec3 DisplayLight::mixed(std::size_t vertex, std::span<const float> levels) const {
  const std::size_t circuits = bundle_.circuits().size();
  const auto light = bundle_.light();
  glm::vec3 sum(0.0f);
  for (const std::uint32_t c : full_) {
    const float* l = &light[(vertex * circuits + c) * 3];
    sum += levels[c] * glm::vec3(l[0], l[1], l[2]);
  }
  if (compact_.empty()) return sum;
  float intensity = 0.0f;
  for (const std::uint32_t c : compact_) {
    const auto code = bundle_.compact_intensity()[vertex * circuits + c];
    intensity += levels[c] * bundle_.circuits()[c].compact_scale * float(model::compact_intensity(code));
  }
  const auto& colour = bundle_.compact_colour()[vertex];
  return sum + intensity * glm::vec3(colour[0], colour[1], colour[2]) / 255.0f;
}

std::size_t DisplayLight::gpu_bytes() const {
  const std::size_t vertices = bundle_.vertices().size();
  return vertices * (full_.size() * 3 * sizeof(float) + (compact_.empty() ? 0 : 4 + compact_.size()));
}

std::size_t DisplayLight::full_form_bytes() const {
  return bundle_.light().size_bytes();
}

}  // namespace walk::render
