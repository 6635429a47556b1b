#pragma once
// Occlusion culling by cluster: which polygons may stand as occluders, found once at load time, and per view
// the occlusion buffer (occlusion_buffer.hpp) filled with those of the nearest clusters in view and the
// clusters it hides. The portal walk bounds what a door shows by the door's screen rectangle; the walls
// round the door hide most of what that rectangle still lets through, and those walls are what this tests
// against. Pure CPU.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"
#include "render/cluster_layout.hpp"
#include "render/occlusion_buffer.hpp"

namespace walk::render {

// Large flat opaque polygons of the units drawn the same at every level (no levels of detail: a simplified
// level could leave a hole where the polygon stood), each with its boundary edges and, per edge, the other
// occluders that continue the surface across it (a wall meeting the next at a corner, a floor meeting it).
struct OccluderSet {
  struct Polygon {
    std::uint32_t corner_first = 0, corner_count = 0;
    std::uint32_t triangle_first = 0, triangle_count = 0;  // into `triangles`, 3 local corner ids each
    std::uint32_t edge_first = 0, edge_count = 0;
    std::uint32_t source = 0;  // the bundle's polygon
  };
  struct Edge {
    std::uint32_t a = 0, b = 0;  // local corner ids
    std::uint32_t partner_first = 0, partner_count = 0;
  };
  std::vector<Polygon> polygons;
  std::vector<glm::vec3> corners;
  std::vector<std::uint32_t> triangles;
  std::vector<Edge> edges;
  std::vector<std::uint32_t> partners;    // occluder polygon ids
  std::vector<std::uint32_t> unit_first;  // unit u's polygons: [unit_first[u], unit_first[u + 1])
};

// From the layout's coarse form (the undiced polygons; the fine form when there is none) and the bundle's
// vertices.
[[nodiscard]] OccluderSet find_occluders(const ClusterLayout& layout,
                                         std::span<const model::VertexRecord> vertices);

class OcclusionCulling {
 public:
  // Per view: fills the buffer with the occluders of the nearest units of `candidates` (units that may be
  // drawn: in the frustum and shown by the portals) that face the eye (or any, with back faces drawn), then
  // marks the candidates it hides. `width` x `height`: the frame's aspect.
  void look(const OccluderSet& set, const ClusterLayout& layout, std::span<const std::uint32_t> candidates,
            const glm::vec3& eye, const glm::mat4& view_projection, int width, int height,
            bool back_faces_culled);
  // After look(): is unit `u` hidden in this view?
  [[nodiscard]] bool hides(std::uint32_t u) const {
    return u < hidden_.size() && hidden_[u] == view_ && view_ != 0;
  }
  [[nodiscard]] std::size_t occluders() const { return occluders_; }
  [[nodiscard]] std::size_t hidden() const { return hidden_count_; }
  [[nodiscard]] const OcclusionBuffer& buffer() const { return buffer_; }

 private:
  OcclusionBuffer buffer_;
  std::vector<std::uint32_t> chosen_;  // per occluder polygon: the view that drew it
  std::vector<std::uint32_t> hidden_;  // per unit: the view that hid it
  std::uint32_t view_ = 0;
  std::size_t occluders_ = 0, hidden_count_ = 0;
  std::vector<std::pair<float, std::uint32_t>> nearest_;
  std::vector<std::uint32_t> drawn_;
  std::vector<OccluderEdge> edges_;
  std::vector<std::uint32_t> group_, slot_, order_;  // this view's surfaces (occluders.cpp)
};

}  // namespace walk::render
