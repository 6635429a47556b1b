#include "compiler/visibility/vis_items.hpp"

#include <algorithm>
#include <glm/glm.hpp>
#include <map>
#include <regex>

namespace walk::compiler {
namespace {

double triangle_area(const std::array<model::Vec3, 3>& t) {
  return 0.5 * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
}

Box united(const Box& a, const Box& b) {
  return {glm::min(a.min, b.min), glm::max(a.max, b.max)};
}

// Splits `ids` (detail polygons) into clusters, appending each as an item.
void split_cluster(std::vector<std::uint32_t> ids, const std::vector<VisPolygon>& polygons, VisItems& out) {
  Box box = polygons[ids.front()].box;
  std::size_t triangles = 0;
  for (const auto id : ids) {
    box = united(box, polygons[id].box);
    triangles += polygons[id].drawn_triangles;
  }
  const model::Vec3 size = box.size();
  const double longest = std::max({size.x, size.y, size.z});
  if (ids.size() > 1 && (triangles > kClusterTriangles || longest > kClusterExtent)) {
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    auto centre = [&](std::uint32_t id) { return polygons[id].box.min[axis] + polygons[id].box.max[axis]; };
    const auto mid = ids.begin() + static_cast<std::ptrdiff_t>(ids.size() / 2);
    std::nth_element(ids.begin(), mid, ids.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return centre(a) < centre(b); });
    std::vector<std::uint32_t> low(ids.begin(), mid), high(mid, ids.end());
    split_cluster(std::move(low), polygons, out);
    split_cluster(std::move(high), polygons, out);
    return;
  }
  VisPolygon item;
  item.detail = true;
  item.box = box;
  item.glass = polygons[ids.front()].glass;
  item.drawn_triangles = triangles;
  for (const auto id : ids)
    item.triangles.insert(item.triangles.end(), polygons[id].triangles.begin(), polygons[id].triangles.end());
  std::sort(ids.begin(), ids.end());
  out.items.push_back(std::move(item));
  out.polygons.push_back(std::move(ids));
}

}  // namespace

std::vector<char> structure_polygons(const std::vector<VisPolygon>& polygons,
                                     std::span<const model::PolygonRecord> records,
                                     std::span<const std::string> group_names,
                                     const VisibilityConfig& config) {
  std::vector<double> area(polygons.size(), 0.0);
  std::map<std::uint32_t, Box> group_box;
  std::map<std::uint32_t, std::vector<double>> group_areas;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (polygons[i].triangles.empty()) continue;
    for (const auto& t : polygons[i].triangles) area[i] += triangle_area(t);
    auto [it, fresh] = group_box.try_emplace(records[i].group, polygons[i].box);
    if (!fresh) it->second = united(it->second, polygons[i].box);
    group_areas[records[i].group].push_back(area[i]);
  }
  // Per group, first match wins.
  enum class Kind { Structure, NamedDetail, Object, BySize };
  std::map<std::uint32_t, Kind> kind_of;
  for (const auto& [group, box] : group_box) {
    const std::string& name = group < group_names.size() ? group_names[group] : std::string();
    Kind kind = Kind::BySize;
    if (config.structure_groups && std::regex_search(name, *config.structure_groups))
      kind = Kind::Structure;
    else if (std::binary_search(config.frame_groups.begin(), config.frame_groups.end(), group))
      kind = Kind::Structure;
    else if (config.detail_groups && std::regex_search(name, *config.detail_groups))
      kind = Kind::NamedDetail;
    else {
      // Small, and made of small faces: an object. A small room (a 2.5 m washroom) is made of whole walls.
      auto& areas = group_areas[group];
      const auto mid = areas.begin() + static_cast<std::ptrdiff_t>(areas.size() / 2);
      std::nth_element(areas.begin(), mid, areas.end());
      const model::Vec3 s = box.size();
      if (std::max({s.x, s.y, s.z}) < config.detail_extent && *mid < kShellFaceArea) kind = Kind::Object;
    }
    kind_of[group] = kind;
  }
  std::vector<char> out(polygons.size(), 0);
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const VisPolygon& p = polygons[i];
    if (p.triangles.empty() || !(p.opaque || p.glass)) continue;
    const Kind kind = kind_of[records[i].group];
    // Glass closes the building's envelope (windows), whatever its group's size.
    const bool sized = kind == Kind::BySize || (kind == Kind::Object && p.glass);
    out[i] = kind == Kind::Structure || (sized && area[i] >= config.detail_area);
  }
  return out;
}

VisItems make_vis_items(std::vector<VisPolygon> polygons, std::span<const model::PolygonRecord> records,
                        const std::vector<char>& structure) {
  VisItems out;
  std::map<std::pair<std::uint32_t, bool>, std::vector<std::uint32_t>> detail;  // (group, glass) -> polygons
  for (std::uint32_t i = 0; i < polygons.size(); ++i) {
    if (polygons[i].triangles.empty()) continue;
    if (structure[i]) {
      out.items.push_back(std::move(polygons[i]));
      out.polygons.push_back({i});
    } else {
      detail[{records[i].group, polygons[i].glass}].push_back(i);
      ++out.detail_polygons;
    }
  }
  out.structure = out.items.size();
  for (auto& [key, ids] : detail) split_cluster(std::move(ids), polygons, out);
  return out;
}

std::vector<model::Vec3> box_corners(const Box& box) {
  std::vector<model::Vec3> out;
  for (int k = 0; k < 8; ++k)
    out.emplace_back(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y,
                     k & 4 ? box.max.z : box.min.z);
  return out;
}

std::vector<Winding> box_faces(const Box& box) {
  std::vector<Winding> faces;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (const double c : {box.min[a], box.max[a]}) {
      Winding f(4);
      for (int k = 0; k < 4; ++k) {
        f[k][a] = c;
        f[k][u] = (k == 1 || k == 2) ? box.max[u] : box.min[u];
        f[k][v] = k >= 2 ? box.max[v] : box.min[v];
      }
      faces.push_back(std::move(f));
      if (box.max[a] == box.min[a]) break;  // a flat box: one face in that plane
    }
  }
  return faces;
}

std::vector<std::array<model::Vec3, 3>> box_shell(const Box& box) {
  std::vector<std::array<model::Vec3, 3>> out;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;  // e_u x e_v = e_a: (u, v) counter-clockwise seen from +a
    const bool flat = box.max[a] == box.min[a];
    for (const bool max_side : {true, false}) {
      auto corner = [&](bool hi_u, bool hi_v) {
        model::Vec3 p;
        p[a] = max_side ? box.max[a] : box.min[a];
        p[u] = hi_u ? box.max[u] : box.min[u];
        p[v] = hi_v ? box.max[v] : box.min[v];
        return p;
      };
      std::array<model::Vec3, 4> q{corner(false, false), corner(true, false), corner(true, true),
                                   corner(false, true)};
      if (!max_side) std::swap(q[1], q[3]);  // facing -a
      out.push_back({q[0], q[1], q[2]});
      out.push_back({q[0], q[2], q[3]});
      if (flat) break;
    }
  }
  return out;
}

bool box_meets_region(const Box& box, const std::vector<Plane>& planes) {
  // Whole box behind one plane: the common case, without building faces.
  for (const auto& p : planes) {
    model::Vec3 far;
    for (int a = 0; a < 3; ++a) far[a] = p.n[a] >= 0.0 ? box.max[a] : box.min[a];
    if (p.distance(far) < -kPlaneEpsilon) return false;
  }
  for (const auto& f : box_faces(box))
    if (!clip_front_all(f, planes).empty()) return true;
  return false;
}

}  // namespace walk::compiler
