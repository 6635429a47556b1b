#include "compiler/radiosity/vertex_light.hpp"

namespace walk::compiler {
namespace {

// Row r of `sums` divided by `area[r]` (rows of no area left empty).
void divide_rows(SparseLight& sums, const std::vector<double>& area) {
  for (std::size_t r = 0; r < sums.rows(); ++r) {
    if (area[r] <= 0.0) {
      sums.clear_row(r);
      continue;
    }
    for (CircuitLight& e : sums.row(r))
      for (double& v : e.rgb) v /= area[r];
  }
}

}  // namespace

SparseLight vertex_radiosity(const PatchSet& patches, const RadiosityResult& result) {
  SparseLight sum(patches.vertices.size());
  std::vector<double> area(patches.vertices.size(), 0.0);
  for (std::size_t p = 0; p < patches.patches.size(); ++p) {
    const Patch& patch = patches.patches[p];
    for (std::uint32_t v : patch.v) {
      area[v] += patch.area;
      sum.add(v, result.radiosity.row(p), patch.area);
    }
  }
  divide_rows(sum, area);
  return sum;
}

model::LightRows polygon_radiosity(const PatchSet& patches, const RadiosityResult& result,
                                   std::size_t polygon_count) {
  SparseLight sum(polygon_count);
  std::vector<double> area(polygon_count, 0.0);
  for (std::size_t p = 0; p < patches.patches.size(); ++p) {
    const Patch& patch = patches.patches[p];
    if (patch.polygon >= polygon_count) continue;
    area[patch.polygon] += patch.area;
    sum.add(patch.polygon, result.radiosity.row(p), patch.area);
  }
  divide_rows(sum, area);
  return sum.to_rows();
}

}  // namespace walk::compiler
