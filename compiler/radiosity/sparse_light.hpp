#pragma once
// Light per row (a patch, a surface sample, a vertex) and circuit in double precision, as the compile
// gathers and solves it: each row a short list of the circuits that reach it, in increasing circuit order
// (model/light_rows.hpp says why sparse). Rows grow by accumulation; different rows may be written by
// different threads at once.
#include <cstdint>
#include <span>
#include <vector>

#include "model/light_rows.hpp"

namespace walk::compiler {

struct CircuitLight {
  std::uint32_t circuit = 0;
  double rgb[3] = {0.0, 0.0, 0.0};
};

class SparseLight {
 public:
  SparseLight() = default;
  explicit SparseLight(std::size_t rows) : rows_(rows) {}
  // A dense table [row][circuit][channel], zeros left out (tests and small callers).
  static SparseLight from_dense(std::span<const double> dense, std::size_t circuits);

  [[nodiscard]] std::size_t rows() const { return rows_.size(); }
  [[nodiscard]] bool empty() const { return rows_.empty(); }
  [[nodiscard]] std::span<const CircuitLight> row(std::size_t r) const { return rows_[r]; }
  [[nodiscard]] std::span<CircuitLight> row(std::size_t r) { return rows_[r]; }
  // Row r's light of `circuit`, an entry of zeros added in order where it has none.
  double* at(std::size_t r, std::uint32_t circuit);
  // Channel k % 3 of circuit k / 3 at row r; 0 where the circuit does not reach it.
  [[nodiscard]] double value(std::size_t r, std::size_t k) const;
  // Row r += scale x `light`.
  void add(std::size_t r, std::span<const CircuitLight> light, double scale = 1.0);
  void clear_row(std::size_t r) { rows_[r].clear(); }
  void set_row(std::size_t r, std::span<const CircuitLight> light) {
    rows_[r].assign(light.begin(), light.end());
  }
  void append_row(std::span<const CircuitLight> light) { rows_.emplace_back(light.begin(), light.end()); }
  // The mean over channels of the sum over circuits: a row's light with every circuit at full, as a scalar.
  [[nodiscard]] double scalar(std::size_t r) const;
  [[nodiscard]] std::size_t entries() const;

  [[nodiscard]] std::vector<double> dense(std::size_t circuits) const;
  // In float for a bundle, all-zero entries left out.
  [[nodiscard]] model::LightRows to_rows() const;

 private:
  std::vector<std::vector<CircuitLight>> rows_;
};

}  // namespace walk::compiler
