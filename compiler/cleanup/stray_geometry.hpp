#pragma once
// Geometry that must not reach clean-up: coordinates that are not numbers or lie beyond any building
// (an error naming the file and line), and faces far from the rest of the model (AutoCAD drawings often
// carry a stray entity kilometres away), which would otherwise set the weld tolerance, the grid's extent
// and the mesh. Strays are found by a robust measure of the model's extent (percentiles of the faces'
// centres, which a few strays cannot move), reported with their count and location, and left out unless
// the scene keeps them (`[model] outliers = "keep"`).
#include <cstddef>
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

// Largest coordinate accepted, metres from the file's origin: 1e8 m (100,000 km) is far beyond any
// national grid (UTM northings reach 1e7 m) and far below where double spacing (1.5e-8 m at 1e8)
// would matter for a 1e-9 m weld.
inline constexpr double kMaxCoordinate = 1e8;

// A face is a stray when its centre lies outside the box of the faces' centres between the 1st and 99th
// percentiles per axis (a few strays cannot move it) by more than kStrayFence times that box's size, and by
// more than kMinStrayMargin metres. The margin is wide on purpose: a tower whose faces crowd into a
// furnished lobby keeps its roof 300 m up; AutoCAD's strays lie kilometres to thousands of kilometres away.
inline constexpr double kStrayFence = 10.0;
inline constexpr double kMinStrayMargin = 1000.0;

// Throws walk::Error naming `file` and the face's source line for the first corner that is not finite or
// lies beyond kMaxCoordinate.
void check_coordinates(const model::Model& model, const std::string& file);

struct StrayStats {
  std::size_t faces = 0;   // faces found stray (and removed unless kept)
  model::Bounds kept;      // the box a face's centre must lie in, metres
  model::Vec3 first{0.0};  // centre of the first stray, for the report
  std::uint32_t first_line = 0;
  [[nodiscard]] std::string summary() const;
};

// Finds the strays and, unless `keep`, removes them.
StrayStats remove_strays(model::Model& model, bool keep);

}  // namespace walk::compiler
