#include "model/light_rows.hpp"

#include <limits>
#include <stdexcept>

namespace walk::model {

std::vector<float> LightRowsView::dense(std::size_t circuits) const {
  std::vector<float> out(rows() * circuits * 3, 0.0f);
  for (std::size_t r = 0; r < rows(); ++r)
    for (const LightEntry& e : row(r))
      for (int c = 0; c < 3; ++c) out[(r * circuits + e.circuit) * 3 + c] = e.rgb[c];
  return out;
}

void LightRowsView::sum_row(std::size_t r, float out[3]) const {
  out[0] = out[1] = out[2] = 0.0f;
  for (const LightEntry& e : row(r))
    for (int c = 0; c < 3; ++c) out[c] += e.rgb[c];
}

void LightRows::add(std::uint32_t circuit, const float rgb[3]) {
  if (rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f) return;
  if (first.empty()) first.push_back(0);
  if (entries.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("light rows: more than 2^32 entries");
  entries.push_back({circuit, {rgb[0], rgb[1], rgb[2]}});
}

void LightRows::end_row() {
  if (first.empty()) first.push_back(0);
  first.push_back(static_cast<std::uint32_t>(entries.size()));
}

LightRows LightRows::from_dense(std::span<const float> dense, std::size_t circuits) {
  LightRows out;
  const std::size_t k = circuits * 3;
  if (k == 0) return out;
  out.first.reserve(dense.size() / k + 1);
  out.first.push_back(0);
  for (std::size_t r = 0; r < dense.size() / k; ++r) {
    for (std::size_t c = 0; c < circuits; ++c) out.add(static_cast<std::uint32_t>(c), &dense[r * k + c * 3]);
    out.end_row();
  }
  return out;
}

void CompactCodes::add(std::uint32_t circuit, std::uint8_t code) {
  if (code == 0) return;
  if (first.empty()) first.push_back(0);
  if (codes.size() >= std::numeric_limits<std::uint32_t>::max() || circuit >= (1u << 24))
    throw std::length_error("compact codes: more than 2^32 entries or 2^24 circuits");
  codes.push_back(circuit << 8 | code);
}

void CompactCodes::end_row() {
  if (first.empty()) first.push_back(0);
  first.push_back(static_cast<std::uint32_t>(codes.size()));
}

}  // namespace walk::model
