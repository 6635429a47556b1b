#include "tools/gen/plan_unit.hpp"

#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <map>

#include "compiler/import/import_model.hpp"
#include "compiler/scene/apply_rules.hpp"
#include "compiler/scene/scene_config.hpp"
#include "model/error.hpp"

namespace walk::gen {
namespace {

struct KnownPlan {
  const char* name;
  const char* scene;  // in config/scenes
  const char* file;   // in the shared data folder
};

// The 2D apartment plan: a real CAD drawing whose walls, doorways (gaps between wall ends) and rooms the
// plan stage of the compiler finds; its windows are placed by its scene config.
constexpr KnownPlan kPlans[] = {
    {"apartment", "apartment-plan.toml", "floorplan-2d-apartment/floorplan.dxf"},
};

// Outline corners closer than this are one corner, metres (the plan builder places them to 1 um).
constexpr double kOutlineJoin = 1e-5;

std::pair<long long, long long> key(glm::dvec2 p) {
  return {std::llround(p.x / kOutlineJoin), std::llround(p.y / kOutlineJoin)};
}

// The outer walls' faces (group "exterior", facing out) stood on the floor: their bottom edges, chained.
std::vector<glm::dvec2> outer_outline(const model::Model& m, const std::string& file) {
  std::map<std::pair<long long, long long>, std::pair<glm::dvec2, glm::dvec2>> next;
  for (const auto& p : m.polygons) {
    if (m.groups[p.group] != "exterior" || p.role != model::Role::Opaque) continue;
    const model::Vec3 n = model::area_vector(p.vertices);
    if (std::abs(n.z) > 1e-9 * glm::length(n)) continue;  // only the vertical faces
    std::vector<glm::dvec2> bottom;
    for (const auto& v : p.vertices)
      if (std::abs(v.z) < kOutlineJoin) bottom.emplace_back(v.x, v.y);
    if (bottom.size() != 2) continue;
    glm::dvec2 a = bottom[0], b = bottom[1];
    const glm::dvec2 d = b - a;
    if (d.y * n.x - d.x * n.y < 0.0) std::swap(a, b);  // outside on the right: counter-clockwise
    next[key(a)] = {a, b};
  }
  std::vector<glm::dvec2> loop;
  if (next.empty())
    throw Error(located(file, 0, "the plan has no outer walls", "draw the walls as closed outlines"));
  glm::dvec2 at = next.begin()->second.first;
  for (std::size_t i = 0; i <= next.size(); ++i) {
    const auto it = next.find(key(at));
    if (it == next.end())
      throw Error(located(file, 0, "the plan's outer walls do not close into one outline",
                          "close the outer wall outline, or use another plan"));
    loop.push_back(at);
    at = it->second.second;
    if (key(at) == key(loop.front())) break;
  }
  if (loop.size() != next.size())
    throw Error(
        located(file, 0, "the plan's outer walls form more than one outline", "use a plan of one building"));
  return loop;
}

}  // namespace

std::vector<std::string> plan_names() {
  std::vector<std::string> names;
  for (const auto& p : kPlans) names.emplace_back(p.name);
  return names;
}

PlanUnit load_plan_unit(const std::string& name, const std::string& scenes_dir, const std::string& data_dir) {
  const KnownPlan* plan = nullptr;
  for (const auto& p : kPlans)
    if (name == p.name) plan = &p;
  if (!plan) {
    std::string known;
    for (const auto& n : plan_names()) known += (known.empty() ? "" : ", ") + n;
    throw Error("--plan: unknown plan '" + name + "' (known: " + known + ")");
  }
  const std::string scene = (std::filesystem::path(scenes_dir) / plan->scene).string();
  const std::string file = (std::filesystem::path(data_dir) / plan->file).string();
  if (!std::filesystem::is_regular_file(scene))
    throw Error(located(scene, 0, "the plan's scene config is missing",
                        "give the repository's config/scenes with --scenes"));
  if (!std::filesystem::is_regular_file(file))
    throw Error(located(file, 0, "the plan file is missing", "give the shared data folder with --data"));
  compiler::SceneConfig config = compiler::load_scene_config(scene);
  config.model_file = std::filesystem::absolute(file).string();
  compiler::ImportReport report;
  PlanUnit unit;
  unit.name = name;
  unit.source = file;
  unit.model = compiler::import_model(config, &report);
  compiler::apply_rules(unit.model, config);
  unit.storey_height = config.plan.wall_height;
  unit.outline = outer_outline(unit.model, file);
  return unit;
}

}  // namespace walk::gen
