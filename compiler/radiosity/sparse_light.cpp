#include "compiler/radiosity/sparse_light.hpp"

#include <algorithm>
#include <iterator>

namespace walk::compiler {

SparseLight SparseLight::from_dense(std::span<const double> dense, std::size_t circuits) {
  const std::size_t k = circuits * 3;
  SparseLight out(k == 0 ? 0 : dense.size() / k);
  for (std::size_t r = 0; r < out.rows(); ++r)
    for (std::uint32_t c = 0; c < circuits; ++c) {
      const double* v = &dense[r * k + c * 3];
      if (v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0) out.rows_[r].push_back({c, {v[0], v[1], v[2]}});
    }
  return out;
}

double* SparseLight::at(std::size_t r, std::uint32_t circuit) {
  auto& row = rows_[r];
  // Rows hold a few circuits: a linear scan from the back finds the place (accumulation mostly appends).
  auto it = row.end();
  while (it != row.begin() && std::prev(it)->circuit >= circuit) --it;
  if (it == row.end() || it->circuit != circuit) it = row.insert(it, CircuitLight{circuit, {0.0, 0.0, 0.0}});
  return it->rgb;
}

double SparseLight::value(std::size_t r, std::size_t k) const {
  for (const CircuitLight& e : rows_[r])
    if (e.circuit == k / 3) return e.rgb[k % 3];
  return 0.0;
}

void SparseLight::add(std::size_t r, std::span<const CircuitLight> light, double scale) {
  for (const CircuitLight& e : light) {
    double* b = at(r, e.circuit);
    for (int c = 0; c < 3; ++c) b[c] += scale * e.rgb[c];
  }
}

double SparseLight::scalar(std::size_t r) const {
  double s = 0.0;
  for (const CircuitLight& e : rows_[r])
    for (const double v : e.rgb) s += v;
  return s / 3.0;
}

std::size_t SparseLight::entries() const {
  std::size_t n = 0;
  for (const auto& row : rows_) n += row.size();
  return n;
}

std::vector<double> SparseLight::dense(std::size_t circuits) const {
  std::vector<double> out(rows_.size() * circuits * 3, 0.0);
  for (std::size_t r = 0; r < rows_.size(); ++r)
    for (const CircuitLight& e : rows_[r])
      for (int c = 0; c < 3; ++c) out[(r * circuits + e.circuit) * 3 + c] = e.rgb[c];
  return out;
}

model::LightRows SparseLight::to_rows() const {
  model::LightRows out;
  out.first.reserve(rows_.size() + 1);
  out.first.push_back(0);
  for (const auto& row : rows_) {
    for (const CircuitLight& e : row) {
      const float rgb[3] = {float(e.rgb[0]), float(e.rgb[1]), float(e.rgb[2])};
      out.add(e.circuit, rgb);
    }
    out.end_row();
  }
  return out;
}

}  // namespace walk::compiler
