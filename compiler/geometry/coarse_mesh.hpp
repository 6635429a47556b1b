#pragma once
// The coarse form of a polygon for the moving display: its fewest triangles (no lighting grid), written with
// the vertices of its diced mesh so that both forms share one vertex buffer and the per-polygon light.
#include <cstdint>
#include <optional>
#include <vector>

#include "compiler/geometry/mesher.hpp"

namespace walk::compiler {

// A coarse vertex is the diced vertex at the same place. Both meshes come from the same outline through the
// same arithmetic, so the match is normally exact; this allows for the last-bit differences of cut points
// computed along a longer chain of cuts. A micrometre is a thousandth of kMinGridGap, the smallest feature
// the mesher keeps, so no two distinct vertices of one mesh are this close.
inline constexpr double kCoarseVertexMatch = 1e-6;

// Indices into `fine.vertices` for the triangles of `coarse`, or nullopt when some coarse vertex has no
// diced vertex within kCoarseVertexMatch (then the caller keeps the diced triangles as the coarse form).
[[nodiscard]] std::optional<std::vector<std::uint32_t>> coarse_triangles(const PolygonMesh& fine,
                                                                         const PolygonMesh& coarse);

}  // namespace walk::compiler
