#include "model/model.hpp"

#include <algorithm>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace walk::model {

const char* role_name(Role role) {
  switch (role) {
    case Role::Opaque:
      return "opaque";
    case Role::Glass:
      return "glass";
    case Role::Opening:
      return "opening";
    case Role::Luminaire:
      return "luminaire";
    case Role::Ignored:
      return "ignored";
  }
  return "unknown";
}

bool parse_role(const std::string& text, Role& out) {
  for (Role r : {Role::Opaque, Role::Glass, Role::Opening, Role::Luminaire, Role::Ignored}) {
    if (text == role_name(r)) {
      out = r;
      return true;
    }
  }
  return false;
}

std::uint32_t Model::group_index(const std::string& name) {
  auto it = std::find(groups.begin(), groups.end(), name);
  if (it != groups.end()) return static_cast<std::uint32_t>(it - groups.begin());
  groups.push_back(name);
  return static_cast<std::uint32_t>(groups.size() - 1);
}

void TextureMap::translate(const Vec3& shift) {
  u_offset -= glm::dot(u_gradient, shift);
  v_offset -= glm::dot(v_gradient, shift);
}

void Bounds::add(const Vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

std::array<Vec3, 4> panel_corners(const Luminaire& l) {
  const Vec3 u = glm::normalize(l.u_axis) * (0.5 * l.width);
  const Vec3 v = glm::normalize(glm::cross(l.normal, l.u_axis)) * (0.5 * l.height);
  return {l.position - u - v, l.position + u - v, l.position + u + v, l.position - u + v};
}

Bounds bounds_of(const Model& model) {
  Bounds b;
  for (const auto& poly : model.polygons)
    for (const auto& v : poly.vertices) b.add(v);
  return b;
}

Vec3 area_vector(const std::vector<Vec3>& loop) {
  Vec3 n{0.0};
  if (loop.size() < 3) return n;
  const Vec3 o = loop.front();
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3 a = loop[i] - o;
    const Vec3 b = loop[(i + 1) % loop.size()] - o;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

}  // namespace walk::model
