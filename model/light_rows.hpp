#pragma once
// Light per row (a vertex, a polygon) and circuit, kept sparse: a row lists only the circuits whose light
// reaches it, in increasing circuit order. A room is lit by its own circuits and a little by its
// neighbours', so a dense rows x circuits table grows with the building squared (the generated M building:
// 3.6 M vertices x 170 circuits x 3 floats, 7.4 GB), while this grows with the building. A circuit left out
// of a row is exactly zero there, so every mix equals the dense one.
#include <cstdint>
#include <span>
#include <vector>

namespace walk::model {

// One circuit's radiosity at a row (W/m2 per channel): the record of LGHT and PLGT.
struct LightEntry {
  std::uint32_t circuit;
  float rgb[3];
};
static_assert(sizeof(LightEntry) == 16);

// Read-only rows over storage owned elsewhere (a mapped bundle, or LightRows): row r's entries are
// entries[first[r], first[r + 1]).
struct LightRowsView {
  std::span<const std::uint32_t> first;  // rows + 1, or empty: no rows
  std::span<const LightEntry> entries;

  [[nodiscard]] std::size_t rows() const { return first.empty() ? 0 : first.size() - 1; }
  [[nodiscard]] bool empty() const { return rows() == 0; }
  [[nodiscard]] std::span<const LightEntry> row(std::size_t r) const {
    return entries.subspan(first[r], first[r + 1] - first[r]);
  }
  // The dense table [row][circuit][channel] (zeros where a circuit is left out): for small scenes and tests;
  // a large building's is the very storage this form avoids.
  [[nodiscard]] std::vector<float> dense(std::size_t circuits) const;
  // Every circuit at full: the sum of a row's entries.
  void sum_row(std::size_t r, float out[3]) const;
};

// Owned rows, appended one after another (what the compiler fills and the bundle writer stores).
struct LightRows {
  std::vector<std::uint32_t> first;  // rows + 1, or empty: no rows
  std::vector<LightEntry> entries;

  [[nodiscard]] LightRowsView view() const { return {first, entries}; }
  [[nodiscard]] std::size_t rows() const { return view().rows(); }
  [[nodiscard]] bool empty() const { return rows() == 0; }
  [[nodiscard]] std::span<const LightEntry> row(std::size_t r) const { return view().row(r); }
  [[nodiscard]] std::vector<float> dense(std::size_t circuits) const { return view().dense(circuits); }

  // Appends an entry to the row being built (circuits in increasing order; an all-zero entry is left out),
  // then closes it. Throws std::length_error past 2^32 entries.
  void add(std::uint32_t circuit, const float rgb[3]);
  void end_row();
  // From a dense table [row][circuit][channel], zeros left out.
  [[nodiscard]] static LightRows from_dense(std::span<const float> dense, std::size_t circuits);
};

// The paper's compact form's 8-bit intensity codes per vertex (model/compact_code.hpp), sparse as LightRows
// is: each entry circuit << 8 | code with code > 0, circuits in increasing order (LINT's record).
struct CompactCodesView {
  std::span<const std::uint32_t> first;  // rows + 1, or empty: no rows
  std::span<const std::uint32_t> codes;

  [[nodiscard]] std::size_t rows() const { return first.empty() ? 0 : first.size() - 1; }
  [[nodiscard]] bool empty() const { return rows() == 0; }
  [[nodiscard]] std::span<const std::uint32_t> row(std::size_t r) const {
    return codes.subspan(first[r], first[r + 1] - first[r]);
  }
};

struct CompactCodes {
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> codes;

  [[nodiscard]] CompactCodesView view() const { return {first, codes}; }
  [[nodiscard]] std::size_t rows() const { return view().rows(); }
  [[nodiscard]] bool empty() const { return rows() == 0; }
  [[nodiscard]] std::span<const std::uint32_t> row(std::size_t r) const { return view().row(r); }
  // Appends circuit's code to the row being built (code 0, no light, is left out), then closes it.
  void add(std::uint32_t circuit, std::uint8_t code);
  void end_row();
};

[[nodiscard]] inline std::uint32_t code_circuit(std::uint32_t entry) {
  return entry >> 8;
}
[[nodiscard]] inline std::uint8_t code_value(std::uint32_t entry) {
  return static_cast<std::uint8_t>(entry & 0xffu);
}

}  // namespace walk::model
