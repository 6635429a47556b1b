#include "compiler/lighting/hidden_vertices.hpp"

#include <vector>

namespace walk::compiler {

std::size_t show_hidden_as_neighbours(std::span<const std::uint32_t> indices,
                                      std::span<const std::uint32_t> sample_vertex,
                                      std::span<const std::uint8_t> hidden, SparseLight& light) {
  enum : std::uint8_t { kNoSample = 0, kSeen = 1, kHidden = 2 };
  std::vector<std::uint8_t> state(light.rows(), kNoSample);
  for (std::size_t i = 0; i < sample_vertex.size() && i < hidden.size(); ++i)
    if (sample_vertex[i] < state.size()) state[sample_vertex[i]] = hidden[i] ? kHidden : kSeen;
  SparseLight neighbours(light.rows());
  std::vector<std::uint32_t> count(light.rows(), 0);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const std::uint32_t u = indices[t + a], w = indices[t + b];
        if (u >= state.size() || w >= state.size() || state[u] != kHidden || state[w] != kSeen) continue;
        neighbours.add(u, light.row(w));
        ++count[u];
      }
  std::size_t changed = 0;
  for (std::size_t v = 0; v < light.rows(); ++v) {
    if (count[v] == 0) continue;
    light.clear_row(v);
    light.add(v, neighbours.row(v), 1.0 / count[v]);
    ++changed;
  }
  return changed;
}

}  // namespace walk::compiler
