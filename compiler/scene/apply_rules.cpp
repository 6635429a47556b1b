#include "compiler/scene/apply_rules.hpp"

#include <algorithm>

namespace walk::compiler {
namespace {

bool matches(const FaceRule& rule, const model::Polygon& p, const std::string& layer) {
  if (rule.color && *rule.color != p.color) return false;
  if (rule.layer && !std::regex_match(layer, *rule.layer)) return false;
  if (rule.name && !std::regex_search(p.name, *rule.name)) return false;
  return true;
}

std::uint32_t material_index(const std::vector<model::Material>& materials, const std::string& name) {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<std::uint32_t>(i);
  return 0;  // load_scene_config already refused rules naming unknown materials
}

}  // namespace

RuleStats apply_rules(model::Model& model, const SceneConfig& config) {
  RuleStats stats;
  model.materials = config.materials;
  for (auto& p : model.polygons) {
    const std::string& layer = p.group < model.groups.size() ? model.groups[p.group] : std::string();
    bool role_set = false, material_set = false;
    for (const auto& rule : config.rules) {
      if (!matches(rule, p, layer)) continue;
      if (rule.role && !role_set) {
        p.role = *rule.role;
        role_set = true;
      }
      if (rule.material && !material_set) {
        p.material = material_index(model.materials, *rule.material);
        material_set = true;
      }
      if (role_set && material_set) break;
    }
    if (config.faces_point_outward) {
      std::reverse(p.vertices.begin(), p.vertices.end());
      for (auto& hole : p.holes) std::reverse(hole.begin(), hole.end());
      ++stats.flipped;
    }
  }
  const auto before = model.polygons.size();
  std::erase_if(model.polygons, [](const model::Polygon& p) { return p.role == model::Role::Ignored; });
  stats.dropped = before - model.polygons.size();
  for (const auto& p : model.polygons) ++stats.per_role[static_cast<std::size_t>(p.role)];
  return stats;
}

}  // namespace walk::compiler
