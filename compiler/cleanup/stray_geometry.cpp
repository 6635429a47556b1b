#include "compiler/cleanup/stray_geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "model/error.hpp"

namespace walk::compiler {
namespace {

model::Vec3 centre_of(const model::Polygon& p) {
  model::Vec3 c(0.0);
  for (const auto& v : p.vertices) c += v;
  return p.vertices.empty() ? c : c / double(p.vertices.size());
}

double quantile(std::vector<double>& values, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * double(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[std::size_t(k)];
}

}  // namespace

void check_coordinates(const model::Model& model, const std::string& file) {
  for (const auto& p : model.polygons) {
    auto check = [&](const model::Vec3& v) {
      for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(v[a]))
          throw Error(located(file, p.source_line,
                              "a corner's coordinate is not a number (" + fmt::format("{}", v[a]) + ")",
                              "fix or delete that entity in the source model"));
        if (std::abs(v[a]) > kMaxCoordinate)
          throw Error(located(
              file, p.source_line,
              fmt::format("a corner lies {:.3g} m from the origin, beyond the {:.0e} m any building can span",
                          std::abs(v[a]), kMaxCoordinate),
              "check the entity (a misplaced point or a wrong unit) and the scene's `units`"));
      }
    };
    for (const auto& v : p.vertices) check(v);
    for (const auto& hole : p.holes)
      for (const auto& v : hole) check(v);
  }
}

std::string StrayStats::summary() const {
  if (faces == 0) return "strays 0";
  return fmt::format(
      "strays {} (first at {:.1f} {:.1f} {:.1f}, source line or face {}; kept box {:.1f} {:.1f} {:.1f} .. "
      "{:.1f} {:.1f} {:.1f})",
      faces, first.x, first.y, first.z, first_line, kept.min.x, kept.min.y, kept.min.z, kept.max.x,
      kept.max.y, kept.max.z);
}

StrayStats remove_strays(model::Model& model, bool keep) {
  StrayStats stats;
  if (model.polygons.empty()) return stats;
  std::vector<model::Vec3> centres;
  centres.reserve(model.polygons.size());
  for (const auto& p : model.polygons) centres.push_back(centre_of(p));
  std::vector<double> axis(centres.size());
  for (int a = 0; a < 3; ++a) {
    for (std::size_t i = 0; i < centres.size(); ++i) axis[i] = centres[i][a];
    const double low = quantile(axis, 0.01), high = quantile(axis, 0.99);
    const double margin = std::max(kStrayFence * (high - low), kMinStrayMargin);
    stats.kept.min[a] = low - margin;
    stats.kept.max[a] = high + margin;
  }
  auto stray = [&](const model::Vec3& c) {
    for (int a = 0; a < 3; ++a)
      if (c[a] < stats.kept.min[a] || c[a] > stats.kept.max[a]) return true;
    return false;
  };
  std::vector<model::Polygon> kept;
  kept.reserve(model.polygons.size());
  for (std::size_t i = 0; i < model.polygons.size(); ++i) {
    if (stray(centres[i])) {
      if (stats.faces++ == 0) {
        stats.first = centres[i];
        stats.first_line = model.polygons[i].source_line;
      }
      if (!keep) continue;
    }
    kept.push_back(std::move(model.polygons[i]));
  }
  model.polygons = std::move(kept);
  return stats;
}

}  // namespace walk::compiler
