#pragma once
// The light the display shows, per vertex and circuit, in the form the compiler chose for each circuit
// (CIRC light_form): the paper's compact form (the vertex's 8-bit colour times an 8-bit logarithmic
// intensity code's value times the circuit's scale, model/compact_code.hpp) where it is within the
// compiler's limit, else LGHT's floats.
// A compact circuit costs a vertex 1 byte instead of 12. This class lays out what the vertex shader reads
// and mixes on the CPU exactly as it does (diagonals, subdivision).
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

class DisplayLight {
 public:
  DisplayLight(const model::Bundle& bundle, DisplayLightForm form);

  // The circuits shown from each form, in circuit order.
  [[nodiscard]] const std::vector<std::uint32_t>& full_circuits() const { return full_; }
  [[nodiscard]] const std::vector<std::uint32_t>& compact_circuits() const { return compact_; }

  // [vertex][full circuit][3] floats for the GPU: LGHT itself when every circuit is full (no copy), else a
  // packed copy of the full circuits (`packed` holds it).
  [[nodiscard]] std::span<const float> full_light(std::vector<float>& packed) const;
  // [vertex][compact circuit] codes for the GPU (empty when no circuit is compact); LCOL is uploaded as is.
  [[nodiscard]] std::vector<std::uint8_t> compact_codes() const;

  // The levels the shader takes, from levels in circuit order: the full circuits' as they are, the compact
  // circuits' multiplied by their scale (so the shader's sum is level x scale x the code's value).
  void split_levels(std::span<const float> levels, std::vector<float>& full,
                    std::vector<float>& compact) const;

  // The mixed radiosity at `vertex` for `levels` (circuit order), as the vertex shader computes it.
  [[nodiscard]] glm::vec3 mixed(std::size_t vertex, std::span<const float> levels) const;

  // Display memory of the light, and what LGHT alone would take.
  [[nodiscard]] std::size_t gpu_bytes() const;
  [[nodiscard]] std::size_t full_form_bytes() const;

 private:
  const model::Bundle& bundle_;
  std::vector<std::uint32_t> full_, compact_;
};

}  // namespace walk::render
