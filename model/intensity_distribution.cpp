#include "model/intensity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/hash.hpp"
#include "model/error.hpp"

namespace walk::model {
namespace {

// Linear interpolation in a strictly increasing grid: the index i with grid[i] <= x < grid[i+1] and the
// weight of grid[i+1]. x must lie within the grid.
std::pair<std::size_t, double> bracket(const std::vector<double>& grid, double x) {
  const auto it = std::upper_bound(grid.begin(), grid.end(), x);
  const std::size_t hi =
      std::min<std::size_t>(std::max<std::ptrdiff_t>(it - grid.begin(), 1), grid.size() - 1);
  const std::size_t lo = hi - 1;
  return {lo, std::clamp((x - grid[lo]) / (grid[hi] - grid[lo]), 0.0, 1.0)};
}

// Steps of the flux quadrature: 0.05 degree in gamma, 0.5 degree in C.
constexpr int kGammaSteps = 3600;
constexpr int kCSteps = 720;

}  // namespace

double IntensityDistribution::candela_at(double gamma, double c) const {
  const std::size_t ng = gamma_deg.size();
  if (ng == 0 || gamma < gamma_deg.front() || gamma > gamma_deg.back()) return 0.0;
  auto along_gamma = [&](std::size_t plane) {
    const double* row = &candela[plane * ng];
    if (ng == 1) return row[0];
    const auto [i, t] = bracket(gamma_deg, gamma);
    return row[i] * (1.0 - t) + row[i + 1] * t;
  };
  if (c_deg.size() == 1) return along_gamma(0);
  double cw = std::fmod(c, 360.0);
  if (cw < 0.0) cw += 360.0;
  const auto [j, t] = bracket(c_deg, cw);
  return along_gamma(j) * (1.0 - t) + along_gamma(j + 1) * t;
}

double IntensityDistribution::flux() const {
  const double dg = 180.0 / kGammaSteps;
  const double rad = std::numbers::pi / 180.0;
  const int c_steps = c_deg.size() == 1 ? 1 : kCSteps;
  const double dc = 360.0 / c_steps;
  double sum = 0.0;
  for (int i = 0; i < kGammaSteps; ++i) {
    const double g = (i + 0.5) * dg;
    double ring = 0.0;
    for (int j = 0; j < c_steps; ++j) ring += candela_at(g, (j + 0.5) * dc);
    // Solid angle of the band: 2 pi (cos g0 - cos g1), shared among the C steps.
    sum += ring / c_steps * 2.0 * std::numbers::pi *
           (std::cos((g - 0.5 * dg) * rad) - std::cos((g + 0.5 * dg) * rad));
  }
  return sum;
}

std::uint64_t IntensityDistribution::hash() const {
  std::uint64_t h = hash_bytes(0x1e5, gamma_deg.data(), gamma_deg.size() * sizeof(double));
  h = hash_bytes(h, c_deg.data(), c_deg.size() * sizeof(double));
  return hash_bytes(h, candela.data(), candela.size() * sizeof(double));
}

void finish(IntensityDistribution& d) {
  auto fail = [&](const std::string& what) { throw Error(located(d.source, 0, what)); };
  if (d.gamma_deg.empty() || d.c_deg.empty()) fail("the intensity table has no angles");
  for (std::size_t i = 0; i < d.gamma_deg.size(); ++i) {
    if (!(d.gamma_deg[i] >= 0.0 && d.gamma_deg[i] <= 180.0))
      fail("vertical angle " + std::to_string(d.gamma_deg[i]) + " is outside 0 to 180 degrees");
    if (i > 0 && !(d.gamma_deg[i] > d.gamma_deg[i - 1])) fail("vertical angles must increase");
  }
  for (std::size_t i = 1; i < d.c_deg.size(); ++i)
    if (!(d.c_deg[i] > d.c_deg[i - 1])) fail("horizontal angles must increase");
  if (d.c_deg.size() > 1 && (d.c_deg.front() != 0.0 || d.c_deg.back() != 360.0))
    fail("horizontal angles must run from 0 to 360 once expanded");
  if (d.candela.size() != d.gamma_deg.size() * d.c_deg.size())
    fail("the intensity table has " + std::to_string(d.candela.size()) + " values, expected " +
         std::to_string(d.gamma_deg.size() * d.c_deg.size()));
  bool any = false;
  for (double v : d.candela) {
    if (!(v >= 0.0 && std::isfinite(v))) fail("an intensity is negative or not a number");
    any = any || v > 0.0;
  }
  if (!any) fail("every intensity is 0: the luminaire emits no light");
  d.lumens = d.flux();
}

}  // namespace walk::model
