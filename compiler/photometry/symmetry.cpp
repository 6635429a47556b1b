#include "compiler/photometry/symmetry.hpp"

#include <algorithm>
#include <cmath>

#include "model/error.hpp"

namespace walk::compiler {
namespace {

// Angles closer than this (degrees) are the same plane: files print angles to a few decimals.
constexpr double kSameAngle = 1e-6;

// The stored angle whose plane shows what is seen at `c` (0..360).
double fold(double c, CSymmetry s) {
  switch (s) {
    case CSymmetry::Quadrant:
      if (c > 180.0) c = 360.0 - c;
      return c > 90.0 ? 180.0 - c : c;
    case CSymmetry::BilateralC0:
      return c > 180.0 ? 360.0 - c : c;
    case CSymmetry::BilateralC90:
      return c < 90.0 ? 180.0 - c : c > 270.0 ? 540.0 - c : c;
    default:
      return c;
  }
}

std::vector<double> images(double a, CSymmetry s) {
  switch (s) {
    case CSymmetry::Quadrant:
      return {a, 180.0 - a, 180.0 + a, 360.0 - a};
    case CSymmetry::BilateralC0:
      return {a, 360.0 - a};
    case CSymmetry::BilateralC90:
      return {a, 180.0 - a, 540.0 - a};
    default:
      return {a};
  }
}

}  // namespace

void expand_symmetry(model::IntensityDistribution& d, CSymmetry symmetry, const std::vector<double>& stored_c,
                     const std::vector<std::vector<double>>& rows) {
  auto fail = [&](const std::string& what) { throw Error(located(d.source, 0, what)); };
  if (stored_c.empty() || stored_c.size() != rows.size()) fail("no horizontal (C) planes");
  if (symmetry == CSymmetry::Rotational) {
    d.c_deg = {0.0};
    d.candela = rows.front();
    return;
  }
  const auto [lo, hi] = [&]() -> std::pair<double, double> {
    switch (symmetry) {
      case CSymmetry::Quadrant:
        return {0.0, 90.0};
      case CSymmetry::BilateralC0:
        return {0.0, 180.0};
      case CSymmetry::BilateralC90:
        return {90.0, 270.0};
      default:
        return {0.0, 360.0};
    }
  }();
  if (std::abs(stored_c.front() - lo) > kSameAngle ||
      (symmetry != CSymmetry::None && std::abs(stored_c.back() - hi) > kSameAngle) || stored_c.back() > 360.0)
    fail("horizontal angles " + std::to_string(stored_c.front()) + " to " + std::to_string(stored_c.back()) +
         " do not match their symmetry (expected " + std::to_string(lo) + " to " + std::to_string(hi) + ")");
  std::vector<double> grid;
  for (double a : stored_c)
    for (double image : images(a, symmetry))
      if (image >= -kSameAngle && image <= 360.0 + kSameAngle) grid.push_back(std::clamp(image, 0.0, 360.0));
  if (symmetry == CSymmetry::None) grid.push_back(360.0);  // the circle closes on C0
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(), [](double a, double b) { return b - a < kSameAngle; }),
             grid.end());
  const std::size_t ng = d.gamma_deg.size();
  d.c_deg = grid;
  d.candela.clear();
  for (double c : grid) {
    double at = fold(c, symmetry);
    if (symmetry == CSymmetry::None && at > stored_c.back() + kSameAngle) at = 0.0;  // past the last plane
    // The stored plane at `at` (or the two around it: folding lands on a stored angle up to round-off).
    const auto it = std::lower_bound(stored_c.begin(), stored_c.end(), at - kSameAngle);
    const std::size_t j = std::min<std::size_t>(it - stored_c.begin(), stored_c.size() - 1);
    if (std::abs(stored_c[j] - at) > kSameAngle) fail("internal: no stored plane at C" + std::to_string(at));
    if (rows[j].size() != ng) fail("a C plane has the wrong number of intensities");
    d.candela.insert(d.candela.end(), rows[j].begin(), rows[j].end());
  }
}

}  // namespace walk::compiler
