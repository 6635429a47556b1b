#include "compiler/geometry/coarse_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace walk::compiler {

std::optional<std::vector<std::uint32_t>> coarse_triangles(const PolygonMesh& fine,
                                                           const PolygonMesh& coarse) {
  // Diced vertices sorted by x: each coarse vertex looks only at those within the match distance in x.
  std::vector<std::uint32_t> by_x(fine.vertices.size());
  for (std::uint32_t i = 0; i < by_x.size(); ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(),
            [&](std::uint32_t a, std::uint32_t b) { return fine.vertices[a][0] < fine.vertices[b][0]; });
  std::vector<std::uint32_t> match(coarse.vertices.size());
  for (std::size_t c = 0; c < coarse.vertices.size(); ++c) {
    const model::Vec3& p = coarse.vertices[c];
    auto it = std::lower_bound(by_x.begin(), by_x.end(), p[0] - kCoarseVertexMatch,
                               [&](std::uint32_t i, double x) { return fine.vertices[i][0] < x; });
    double best = kCoarseVertexMatch * kCoarseVertexMatch;
    std::optional<std::uint32_t> found;
    for (; it != by_x.end() && fine.vertices[*it][0] <= p[0] + kCoarseVertexMatch; ++it) {
      const model::Vec3 d = fine.vertices[*it] - p;
      const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (d2 <= best) {
        best = d2;
        found = *it;
      }
    }
    if (!found) return std::nullopt;
    match[c] = *found;
  }
  std::vector<std::uint32_t> out;
  out.reserve(coarse.triangles.size());
  for (std::uint32_t i : coarse.triangles) out.push_back(match[i]);
  return out;
}

}  // namespace walk::compiler
