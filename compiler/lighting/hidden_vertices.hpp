#pragma once
// A vertex no view sees (most of its gather rays meet backs: the ceiling behind a hung lamp's panel, the
// floor under a box) is still a corner of triangles that a view does see, across the panel's outline or the
// box's foot. Showing its own light there ramps those triangles from dark, which drew a dark band around
// every hung panel (walk bench image --error-map). It shows its seen neighbours' light instead; only the
// display changes, the patches having shot what it really receives.
#include <cstddef>
#include <cstdint>
#include <span>

#include "compiler/radiosity/sparse_light.hpp"

namespace walk::compiler {

// `light`: a row per vertex; sample i is vertex `sample_vertex[i]`, hidden where `hidden[i]`; `indices`:
// the display's triangles. Each hidden vertex that shares a triangle with a seen sample takes the mean of
// those neighbours' rows (counted once per triangle they share); other rows stay. Returns how many changed.
std::size_t show_hidden_as_neighbours(std::span<const std::uint32_t> indices,
                                      std::span<const std::uint32_t> sample_vertex,
                                      std::span<const std::uint8_t> hidden, SparseLight& light);

}  // namespace walk::compiler
