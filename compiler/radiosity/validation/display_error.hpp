#pragma once
// Error of what the display shows: radiosity interpolated across each triangle from its vertices, evaluated
// at fixed probe points on every polygon, compared with a reference solution evaluated at the same points.
// Probes are placed by polygon, so solutions diced at different patch sizes are comparable.
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

// A solution as the display sees it: triangles grouped by polygon, one scalar value per vertex.
struct ShadedMesh {
  std::vector<model::Vec3> vertices;
  std::vector<double> value;                                  // per vertex
  std::vector<std::vector<std::uint32_t>> polygon_triangles;  // per polygon: vertex indices, 3 per triangle
};

struct ErrorProbe {  // a point where the display's error is measured
  std::uint32_t polygon;
  model::Vec3 position;
};

// Probes spread uniformly by area over each polygon of `mesh`, `per_square_metre` of them (at least one per
// polygon), from a fixed seed.
[[nodiscard]] std::vector<ErrorProbe> make_probes(const ShadedMesh& mesh, double per_square_metre);

// Interpolated value at each probe (NaN where no triangle of the probe's polygon contains it).
[[nodiscard]] std::vector<double> evaluate(const ShadedMesh& mesh, const std::vector<ErrorProbe>& probes);

struct DisplayError {
  double rms = 0.0;  // root mean square of (value - reference) over probes, in units of the reference mean
  double mean_ratio = 0.0;  // mean value / mean reference
  std::size_t probes = 0;
};

[[nodiscard]] DisplayError compare(const std::vector<double>& values, const std::vector<double>& reference);

}  // namespace walk::compiler
