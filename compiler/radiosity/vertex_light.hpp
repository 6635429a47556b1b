#pragma once
// From patch radiosities to what the display interpolates: each vertex takes the area-weighted mean of the
// patches around it (patches share vertices only within their polygon, so light never bleeds across a corner
// from one wall to the next), and each polygon the area-weighted mean of its patches (its coarse colour).
#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "compiler/radiosity/sparse_light.hpp"

namespace walk::compiler {

// A row per vertex of `patches`, in double (the light stage adds gathered direct light before storing it).
[[nodiscard]] SparseLight vertex_radiosity(const PatchSet& patches, const RadiosityResult& result);

// A row per polygon 0..polygon_count-1, as floats for the bundle.
[[nodiscard]] model::LightRows polygon_radiosity(const PatchSet& patches, const RadiosityResult& result,
                                                 std::size_t polygon_count);

}  // namespace walk::compiler
