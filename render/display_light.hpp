#pragma once
// The light the display shows, per vertex and circuit, in the form the compiler chose for each circuit
// (CIRC light_form): the paper's compact form (the vertex's 8-bit colour times an 8-bit logarithmic
// intensity code's value times the circuit's scale, model/compact_code.hpp) where it is within the
// compiler's limit, else LGHT's floats.
// Each vertex keeps only the circuits that reach it (non-zero light or code): in a building most
// vertices see one or two of its circuits (the generated S building: 1.7 of 34 on average), so the vertex
// shader loops over those and not over every circuit, and the circuit count is bounded by the levels
// uniform alone. Leaving out zeros changes no sum, so the mix is the dense one exactly. This class lays out
// what the vertex shader reads and mixes on the CPU exactly as it does (diagonals, subdivision).
#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle.hpp"

namespace walk::render {

enum class DisplayLightForm {
  AsCompiled,  // each circuit as its CIRC record says
  Full,        // every circuit from LGHT: the compile's answer without the compact form's error
};

// A vertex's first entry in each of the two lists below (the vertex attribute a_light_first); a vertex's
// entries follow one another and its last one is marked, so 8 bytes a vertex say where its light is.
struct VertexLightRange {
  static constexpr std::uint32_t kNone = 0xffffffffu;  // no circuit reaches the vertex in that form
  std::uint32_t full_first = kNone, compact_first = kNone;
};
// One circuit shown full at one vertex: its radiosity and the circuit's index, plus kLastFullEntry on a
// vertex's last entry (a float, exact below 2^24, so one RGBA32F texel holds the entry).
struct FullLightEntry {
  float rgb[3];
  float circuit;
};
inline constexpr float kLastFullEntry = 1048576.0f;  // 2^20, above any circuit index
// One circuit shown compact at one vertex: circuit << 8 | code (code > 0), plus kLastCompactEntry on a
// vertex's last entry.
using CompactLightEntry = std::uint32_t;
inline constexpr std::uint32_t kLastCompactEntry = 0x80000000u;

class DisplayLight {
 public:
  DisplayLight(const model::Bundle& bundle, DisplayLightForm form);

  // The circuits shown from each form, in circuit order.
  [[nodiscard]] const std::vector<std::uint32_t>& full_circuits() const { return full_; }
  [[nodiscard]] const std::vector<std::uint32_t>& compact_circuits() const { return compact_; }

  // Per vertex, where its entries start; the entries in vertex order, each vertex's in circuit order.
  [[nodiscard]] const std::vector<VertexLightRange>& ranges() const { return ranges_; }
  [[nodiscard]] const std::vector<FullLightEntry>& full_entries() const { return full_entries_; }
  [[nodiscard]] const std::vector<CompactLightEntry>& compact_entries() const { return compact_entries_; }

  // The levels the shader takes, indexed by circuit: a full circuit's as it is, a compact circuit's
  // multiplied by its scale (so the shader's sum is level x scale x the code's value).
  void shader_levels(std::span<const float> levels, std::vector<float>& out) const;

  // The mixed radiosity at `vertex` for `levels` (circuit order), as the vertex shader computes it.
  [[nodiscard]] glm::vec3 mixed(std::size_t vertex, std::span<const float> levels) const;

  // The coarse level's flat light: PLGT (or, where the bundle lacks it, each polygon's mean of its
  // vertices), every circuit as floats, kept sparse like the vertices' and mixed in the vertex shader the
  // same way, so a dimmer turned while the viewer walks costs one upload of the levels. The shader's levels
  // carry a compact circuit's scale (shader_levels), so a compact circuit's polygon entries are stored
  // divided by it.
  [[nodiscard]] const std::vector<std::uint32_t>& polygon_first() const { return polygon_first_; }
  [[nodiscard]] const std::vector<FullLightEntry>& polygon_entries() const { return polygon_entries_; }
  // The coarse light of `polygon` for `levels` (circuit order), as the vertex shader mixes it.
  [[nodiscard]] glm::vec3 polygon_mixed(std::size_t polygon, std::span<const float> levels) const;

  // Display memory of the light, and what LGHT alone would take.
  [[nodiscard]] std::size_t gpu_bytes() const;
  [[nodiscard]] std::size_t full_form_bytes() const;

 private:
  const model::Bundle& bundle_;
  std::vector<std::uint32_t> full_, compact_;
  std::vector<VertexLightRange> ranges_;
  std::vector<FullLightEntry> full_entries_;
  std::vector<CompactLightEntry> compact_entries_;
  std::vector<std::uint32_t> polygon_first_;  // per polygon, its first entry in polygon_entries_
  std::vector<FullLightEntry> polygon_entries_;
};

}  // namespace walk::render
