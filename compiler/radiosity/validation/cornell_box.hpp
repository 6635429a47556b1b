#pragma once
// The measured Cornell box (Cornell University Program of Computer Graphics): geometry in millimetres,
// spectral reflectances and the light's emission spectrum, turned into RGB patches for validating the solver.
// RGB here is the mean over three bands: blue 400-500 nm, green 500-600 nm, red 600-700 nm.
#include <string>
#include <vector>

#include "compiler/radiosity/patch_set.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct CornellSurface {
  std::string name;
  std::string material;               // white, green, red, emitter
  std::vector<model::Vec3> vertices;  // metres, counter-clockwise about the surface's visible side
};

struct CornellBox {
  std::vector<CornellSurface> surfaces;
  model::Rgb white{0.0}, green{0.0}, red{0.0};
  model::Rgb light_reflectance{0.78};
  model::Rgb emission{0.0};  // band means of the emission spectrum (relative units, used as W/m2)
};

// Reads cornell_box_geometry.txt and reflectance_spectra.csv; throws walk::Error naming file and line.
[[nodiscard]] CornellBox load_cornell_box(const std::string& geometry_path, const std::string& spectra_path);

// Dices every surface at `grid` metres into patches (polygon index = surface index). Non-planar quads (the
// measured red wall is 3.2 mm off) are split into two planar triangles so no crack opens at the joints.
[[nodiscard]] PatchSet cornell_patches(const CornellBox& box, double grid,
                                       std::vector<AreaEmitter>& emitters);

}  // namespace walk::compiler
