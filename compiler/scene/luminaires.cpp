#include "compiler/scene/luminaires.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <map>
#include <optional>

#include "compiler/geometry/mesher.hpp"

namespace walk::compiler {
namespace {

// A face counts as horizontal when its unit normal's z is within this of +-1 (about 2.6 degrees).
constexpr double kHorizontalCosine = 0.999;

double signed_area_xy(const std::vector<model::Vec3>& v) {
  double a = 0.0;
  for (std::size_t i = 0, n = v.size(); i < n; ++i)
    a += v[i].x * v[(i + 1) % n].y - v[(i + 1) % n].x * v[i].y;
  return 0.5 * a;
}

bool inside_xy(const std::vector<model::Vec3>& v, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y > y) != (v[j].y > y) && x < (v[j].x - v[i].x) * (y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
      in = !in;
  }
  return in;
}

// Area centroid in xy of a simple polygon; falls back to the vertex mean for a degenerate one.
model::Vec3 centroid_xy(const std::vector<model::Vec3>& v) {
  const double a = signed_area_xy(v);
  model::Vec3 mean(0.0);
  for (const auto& p : v) mean += p / double(v.size());
  if (std::abs(a) < 1e-12) return mean;
  double cx = 0.0, cy = 0.0;
  for (std::size_t i = 0, n = v.size(); i < n; ++i) {
    const auto& p = v[i];
    const auto& q = v[(i + 1) % n];
    const double cross = p.x * q.y - q.x * p.y;
    cx += (p.x + q.x) * cross;
    cy += (p.y + q.y) * cross;
  }
  return {cx / (6.0 * a), cy / (6.0 * a), mean.z};
}

std::optional<model::Luminaire> panel_for_group(const model::Model& model, std::uint32_t group,
                                                const PanelsPerGroup& cfg) {
  const model::Polygon* floor = nullptr;
  double floor_area = 0.0;
  for (const auto& p : model.polygons) {
    if (p.group != group || p.role != model::Role::Opaque) continue;
    if (polygon_normal(p.vertices).z < kHorizontalCosine) continue;
    const double a = std::abs(signed_area_xy(p.vertices));
    if (a > floor_area) {
      floor_area = a;
      floor = &p;
    }
  }
  if (!floor) return std::nullopt;
  model::Vec3 c = centroid_xy(floor->vertices);
  if (!inside_xy(floor->vertices, c.x, c.y)) {  // L-shaped room: use the middle of its first edge's ear
    const auto& v = floor->vertices;
    c = (v[0] + v[1] + v[2]) / 3.0;
  }
  std::optional<double> ceiling;
  for (const auto& p : model.polygons) {
    if (p.group != group || p.role == model::Role::Opening) continue;
    if (polygon_normal(p.vertices).z > -kHorizontalCosine) continue;
    const double z = p.vertices[0].z;
    if (z <= c.z + cfg.drop || !inside_xy(p.vertices, c.x, c.y)) continue;
    if (!ceiling || z < *ceiling) ceiling = z;
  }
  if (!ceiling) return std::nullopt;
  model::Luminaire l;
  l.name = "panel:" + model.groups[group];
  l.position = {c.x, c.y, *ceiling - cfg.drop};
  l.normal = {0.0, 0.0, -1.0};
  l.u_axis = {1.0, 0.0, 0.0};
  l.width = cfg.width;
  l.height = cfg.height;
  l.power = cfg.colour * cfg.power;
  return l;
}

}  // namespace

LuminaireStats add_luminaires(model::Model& model, const SceneConfig& config) {
  LuminaireStats stats;
  // Luminaires the importer found keep their circuit (and its default level) unless a rule claims them.
  const std::vector<model::Circuit> imported_circuits = model.circuits;
  std::vector<model::Circuit> default_circuit;
  for (const auto& l : model.luminaires)
    default_circuit.push_back(l.circuit < imported_circuits.size() ? imported_circuits[l.circuit]
                                                                   : model::Circuit{"imported", 1.0});
  for (std::size_t i = 0; i < config.luminaires.size(); ++i) {
    model::Luminaire l = config.luminaires[i];
    l.position -= model.origin;  // config positions are world coordinates
    model.luminaires.push_back(l);
    default_circuit.push_back({config.luminaire_circuits[i], 1.0});
    ++stats.explicit_panels;
  }
  if (config.panels.enabled) {
    for (std::uint32_t g = 0; g < model.groups.size(); ++g) {
      if (config.panels.exclude_groups && std::regex_search(model.groups[g], *config.panels.exclude_groups))
        continue;
      const auto panel = panel_for_group(model, g, config.panels);
      if (!panel) {
        ++stats.groups_without_ceiling;
        spdlog::warn("room '{}': no floor with a ceiling above it, so no ceiling panel was added",
                     model.groups[g]);
        continue;
      }
      model.luminaires.push_back(*panel);
      default_circuit.push_back({model.groups[g], 1.0});
      ++stats.added_per_group;
    }
  }
  // Circuits: the first [[circuits]] rule matching a luminaire's name, else its default circuit.
  model.circuits.clear();
  std::map<std::string, std::uint32_t> circuit_index;
  for (std::size_t i = 0; i < model.luminaires.size(); ++i) {
    model::Circuit circuit = default_circuit[i];
    for (const auto& rule : config.circuits) {
      if (std::regex_search(model.luminaires[i].name, rule.luminaires)) {
        circuit = {rule.name, rule.default_level};
        break;
      }
    }
    auto [it, added] = circuit_index.emplace(circuit.name, static_cast<std::uint32_t>(model.circuits.size()));
    if (added) model.circuits.push_back(circuit);
    model.luminaires[i].circuit = it->second;
  }
  return stats;
}

}  // namespace walk::compiler
