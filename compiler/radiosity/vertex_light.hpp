#pragma once
// From patch radiosities to what the display interpolates: each vertex takes the area-weighted mean of the
// patches around it (patches share vertices only within their polygon, so light never bleeds across a corner
// from one wall to the next), and each polygon the area-weighted mean of its patches (its coarse colour).
#include <vector>

#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/progressive_solver.hpp"

namespace walk::compiler {

// [vertex][circuit][channel], as floats for the bundle.
[[nodiscard]] std::vector<float> vertex_radiosity(const PatchSet& patches, const RadiosityResult& result);

// [polygon][circuit][channel] for polygons 0..polygon_count-1.
[[nodiscard]] std::vector<float> polygon_radiosity(const PatchSet& patches, const RadiosityResult& result,
                                                   std::size_t polygon_count);

}  // namespace walk::compiler
