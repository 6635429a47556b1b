#include "compiler/radiosity/vertex_light.hpp"

namespace walk::compiler {

std::vector<float> vertex_radiosity(const PatchSet& patches, const RadiosityResult& result) {
  const std::size_t K = result.circuits * 3;
  std::vector<double> sum(patches.vertices.size() * K, 0.0);
  std::vector<double> area(patches.vertices.size(), 0.0);
  for (std::size_t p = 0; p < patches.patches.size(); ++p) {
    const Patch& patch = patches.patches[p];
    for (std::uint32_t v : patch.v) {
      area[v] += patch.area;
      for (std::size_t k = 0; k < K; ++k) sum[v * K + k] += patch.area * result.radiosity[p * K + k];
    }
  }
  std::vector<float> out(sum.size(), 0.0f);
  for (std::size_t v = 0; v < area.size(); ++v)
    if (area[v] > 0.0)
      for (std::size_t k = 0; k < K; ++k) out[v * K + k] = static_cast<float>(sum[v * K + k] / area[v]);
  return out;
}

std::vector<float> polygon_radiosity(const PatchSet& patches, const RadiosityResult& result,
                                     std::size_t polygon_count) {
  const std::size_t K = result.circuits * 3;
  std::vector<double> sum(polygon_count * K, 0.0);
  std::vector<double> area(polygon_count, 0.0);
  for (std::size_t p = 0; p < patches.patches.size(); ++p) {
    const Patch& patch = patches.patches[p];
    if (patch.polygon >= polygon_count) continue;
    area[patch.polygon] += patch.area;
    for (std::size_t k = 0; k < K; ++k)
      sum[patch.polygon * K + k] += patch.area * result.radiosity[p * K + k];
  }
  std::vector<float> out(sum.size(), 0.0f);
  for (std::size_t i = 0; i < polygon_count; ++i)
    if (area[i] > 0.0)
      for (std::size_t k = 0; k < K; ++k) out[i * K + k] = static_cast<float>(sum[i * K + k] / area[i]);
  return out;
}

}  // namespace walk::compiler
