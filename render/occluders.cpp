#include "render/occluders.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>
#include <tuple>

#include "model/model.hpp"

namespace walk::render {
namespace {

// Polygons smaller than this (square metres) are not occluders: a wall panel is metres across, and the many
// small faces of furniture would cost more to rasterise than they hide.
constexpr double kMinOccluderArea = 0.5;
// A polygon whose corners lie this far (metres) off its plane is not used: its depth bound, moved back to
// its farthest corner, would hide little. Correctness does not rest on it (occlusion_buffer.cpp bounds
// every corner).
constexpr double kFlatTolerance = 1e-2;
// Edge ends are matched on a grid of this pitch (metres): two polygons whose edges meet within it continue
// one surface, as the compiler treats openings under kCrackRadius (1 mm) as closed. Ends straddling a grid
// line do not match, which leaves an edge open: less hidden, never more.
constexpr double kSharedEdgeGrid = 1e-4;
// Occluder polygons one view rasterises, nearest units first: enough for the walls of the room the eye is
// in and the next (measured on the generated M building: `walk bench render`, `occlusion` rows).
constexpr std::size_t kMaxOccluders = 64;
// Buffer pixels across (the rows follow the frame's aspect): 112 x 63 for 16:9, about 11 x 11 pixels of a
// 1280 x 720 frame each. On M, 256 columns cost 2.5 ms a view and hid no more.
constexpr int kBufferColumns = 112;
// A triangle whose plane passes this close to the eye (metres) is seen edge on: not used as an occluder,
// whichever way the rounding of its normal would turn it.
constexpr double kFacingSlack = 1e-4;

using GridPoint = std::array<std::int64_t, 3>;

GridPoint grid_point(const glm::vec3& p) {
  return {std::llround(double(p.x) / kSharedEdgeGrid), std::llround(double(p.y) / kSharedEdgeGrid),
          std::llround(double(p.z) / kSharedEdgeGrid)};
}

// A unit drawn at every level by its own polygons: its levels of detail repeat its own range.
bool same_at_every_level(const LaidOutForm& form, std::uint32_t u) {
  if (form.lod.empty()) return true;
  for (const IndexRange& r : form.lod[u])
    if (r.first != form.opaque[u].first || r.count != form.opaque[u].count) return false;
  return true;
}

}  // namespace

OccluderSet find_occluders(const ClusterLayout& layout, std::span<const model::VertexRecord> vertices) {
  OccluderSet set;
  const LaidOutForm& form = layout.coarse.empty() ? layout.fine : layout.coarse;
  const std::size_t units = layout.units();
  // Polygons by unit, in unit order.
  std::vector<std::uint32_t> count(units + 1, 0);
  for (const std::uint32_t u : layout.unit_of_polygon)
    if (u < units) ++count[u + 1];
  std::partial_sum(count.begin(), count.end(), count.begin());
  std::vector<std::uint32_t> by_unit(count.back());
  {
    std::vector<std::uint32_t> next(count.begin(), count.end() - 1);
    for (std::uint32_t p = 0; p < layout.unit_of_polygon.size(); ++p)
      if (layout.unit_of_polygon[p] < units) by_unit[next[layout.unit_of_polygon[p]]++] = p;
  }
  auto vertex_of = [&](std::uint32_t index) -> std::int64_t {
    const std::uint32_t v =
        form.vertices.empty() ? index : (index < form.vertices.size() ? form.vertices[index] : UINT32_MAX);
    return v < vertices.size() ? std::int64_t(v) : -1;
  };
  auto position = [&](std::int64_t v) {
    const float* p = vertices[std::size_t(v)].position;
    return glm::vec3(p[0], p[1], p[2]);
  };

  struct EdgeRecord {
    GridPoint lo, hi;
    std::uint32_t polygon, a, b;
    bool forward;  // a is at lo
  };
  std::vector<EdgeRecord> edge_records;
  set.unit_first.assign(units + 1, 0);
  std::vector<std::int64_t> ids;
  for (std::uint32_t u = 0; u < units; ++u) {
    set.unit_first[u] = std::uint32_t(set.polygons.size());
    if (!same_at_every_level(form, u)) continue;
    for (std::uint32_t k = count[u]; k < count[u + 1]; ++k) {
      const std::uint32_t p = by_unit[k];
      const model::PolygonRecord& rec = form.polygons[p];
      if (rec.role != std::uint32_t(model::Role::Opaque) || rec.index_count < 3) continue;
      // Drawn by the fine form too (patch frames draw it): a polygon one form leaves out hides nothing there.
      if (layout.fine.polygons.size() <= p || layout.fine.polygons[p].index_count == 0) continue;
      if (std::uint64_t(rec.first_index) + rec.index_count > form.indices.size()) continue;
      ids.clear();
      bool valid = true;
      for (std::uint32_t i = rec.first_index; i < rec.first_index + rec.index_count; ++i) {
        const std::int64_t v = vertex_of(form.indices[i]);
        valid = valid && v >= 0;
        ids.push_back(v);
      }
      if (!valid) continue;
      // Area and normal from the triangles' winding (the front side the GPU keeps).
      glm::dvec3 sum(0.0);
      for (std::size_t t = 0; t + 2 < ids.size(); t += 3) {
        const glm::dvec3 a(position(ids[t])), b(position(ids[t + 1])), c(position(ids[t + 2]));
        sum += glm::cross(b - a, c - a);
      }
      const double area = 0.5 * glm::length(sum);
      if (!(area >= kMinOccluderArea)) continue;
      const glm::dvec3 normal = sum / glm::length(sum);
      const glm::dvec3 anchor(position(ids.front()));
      bool flat = true;
      for (std::size_t t = 0; t + 2 < ids.size() && flat; t += 3) {
        const glm::dvec3 a(position(ids[t])), b(position(ids[t + 1])), c(position(ids[t + 2]));
        flat = glm::dot(glm::cross(b - a, c - a), normal) >= 0.0;
        for (const glm::dvec3& q : {a, b, c})
          flat = flat && std::abs(glm::dot(q - anchor, normal)) <= kFlatTolerance;
      }
      if (!flat) continue;
      // Local corners.
      std::vector<std::int64_t> corners(ids);
      std::sort(corners.begin(), corners.end());
      corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
      OccluderSet::Polygon poly;
      poly.source = p;
      poly.corner_first = std::uint32_t(set.corners.size());
      poly.corner_count = std::uint32_t(corners.size());
      poly.triangle_first = std::uint32_t(set.triangles.size());
      poly.triangle_count = std::uint32_t(ids.size() / 3);
      for (const std::int64_t v : corners) set.corners.push_back(position(v));
      const auto id = std::uint32_t(set.polygons.size());
      for (std::size_t t = 0; t + 2 < ids.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
          const auto local = [&](std::int64_t v) {
            return std::uint32_t(std::lower_bound(corners.begin(), corners.end(), v) - corners.begin());
          };
          const std::uint32_t a = local(ids[t + std::size_t(k)]),
                              b = local(ids[t + std::size_t((k + 1) % 3)]);
          set.triangles.push_back(a);
          GridPoint ga = grid_point(set.corners[poly.corner_first + a]);
          GridPoint gb = grid_point(set.corners[poly.corner_first + b]);
          if (ga == gb) continue;  // shorter than the grid: no edge to cross
          edge_records.push_back(ga < gb ? EdgeRecord{ga, gb, id, a, b, true}
                                         : EdgeRecord{gb, ga, id, a, b, false});
        }
      set.polygons.push_back(poly);
    }
  }
  set.unit_first[units] = std::uint32_t(set.polygons.size());

  // An edge one triangle of a polygon has is its boundary. Its partners are the other occluders that cover
  // the other side of it: one with a triangle on each side of the edge (the edge crosses its inside), or one
  // whose boundary runs along it the other way (a consistently wound surface, a wall meeting a floor). Both
  // facing the eye, such a partner lies across the edge on the screen too, so the two leave no gap there.
  std::sort(edge_records.begin(), edge_records.end(), [](const EdgeRecord& x, const EdgeRecord& y) {
    return std::tie(x.lo, x.hi, x.polygon) < std::tie(y.lo, y.hi, y.polygon);
  });
  struct Boundary {
    std::uint32_t polygon, a, b;
    std::vector<std::uint32_t> partners;
  };
  std::vector<Boundary> boundaries;
  struct Side {
    std::uint32_t polygon;
    std::size_t count;
    bool forward;
  };
  std::vector<Side> sides;
  for (std::size_t i = 0; i < edge_records.size();) {
    std::size_t j = i;
    while (j < edge_records.size() && edge_records[j].lo == edge_records[i].lo &&
           edge_records[j].hi == edge_records[i].hi)
      ++j;
    sides.clear();
    for (std::size_t k = i; k < j;) {
      std::size_t m = k;
      while (m < j && edge_records[m].polygon == edge_records[k].polygon) ++m;
      sides.push_back({edge_records[k].polygon, m - k, edge_records[k].forward});
      k = m;
    }
    for (std::size_t k = i, side = 0; k < j; k += sides[side].count, ++side) {
      if (sides[side].count != 1) continue;
      Boundary b{edge_records[k].polygon, edge_records[k].a, edge_records[k].b, {}};
      for (const Side& other : sides)
        if (other.polygon != b.polygon && (other.count > 1 || other.forward != sides[side].forward))
          b.partners.push_back(other.polygon);
      boundaries.push_back(std::move(b));
    }
    i = j;
  }
  std::stable_sort(boundaries.begin(), boundaries.end(),
                   [](const Boundary& x, const Boundary& y) { return x.polygon < y.polygon; });
  for (std::size_t i = 0; i < boundaries.size(); ++i) {
    const Boundary& b = boundaries[i];
    OccluderSet::Polygon& poly = set.polygons[b.polygon];
    if (poly.edge_count == 0) poly.edge_first = std::uint32_t(set.edges.size());
    ++poly.edge_count;
    set.edges.push_back({b.a, b.b, std::uint32_t(set.partners.size()), std::uint32_t(b.partners.size())});
    set.partners.insert(set.partners.end(), b.partners.begin(), b.partners.end());
  }
  return set;
}

void OcclusionCulling::look(const OccluderSet& set, const ClusterLayout& layout,
                            std::span<const std::uint32_t> candidates, const glm::vec3& eye,
                            const glm::mat4& view_projection, int width, int height, bool back_faces_culled) {
  if (++view_ == 0) {  // the stamps wrapped: start them again
    std::fill(chosen_.begin(), chosen_.end(), 0u);
    std::fill(hidden_.begin(), hidden_.end(), 0u);
    view_ = 1;
  }
  chosen_.resize(set.polygons.size(), 0u);
  hidden_.resize(layout.units(), 0u);
  occluders_ = 0;
  hidden_count_ = 0;
  buffer_.clear(view_projection, width, height, kBufferColumns);

  // The nearest candidates with occluders, by their boxes' distance from the eye.
  nearest_.clear();
  for (const std::uint32_t u : candidates) {
    if (u + 1 >= set.unit_first.size() || set.unit_first[u] == set.unit_first[u + 1]) continue;
    nearest_.push_back({distance_to(eye, layout.boxes[u]), u});
  }
  std::sort(nearest_.begin(), nearest_.end());
  drawn_.clear();
  const glm::dvec3 e(eye);
  for (const auto& [distance, u] : nearest_) {
    if (drawn_.size() >= kMaxOccluders) break;
    for (std::uint32_t p = set.unit_first[u]; p < set.unit_first[u + 1]; ++p) {
      const OccluderSet::Polygon& poly = set.polygons[p];
      const glm::vec3* corner = set.corners.data() + poly.corner_first;
      bool drawn = true;
      // Culled back faces are not drawn, so they hide nothing: every triangle must face the eye.
      for (std::uint32_t t = 0; t < poly.triangle_count && drawn && back_faces_culled; ++t) {
        const std::uint32_t* v = set.triangles.data() + poly.triangle_first + 3 * t;
        const glm::dvec3 a(corner[v[0]]), b(corner[v[1]]), c(corner[v[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        drawn = len > 0.0 && glm::dot(n, e - a) > kFacingSlack * len;
      }
      if (!drawn) continue;
      chosen_[p] = view_;
      drawn_.push_back(p);
    }
  }
  // Surfaces: the chosen polygons joined by their shared edges (union-find over this view's few).
  group_.assign(drawn_.size(), 0);
  std::iota(group_.begin(), group_.end(), 0u);
  slot_.resize(set.polygons.size());
  for (std::uint32_t k = 0; k < drawn_.size(); ++k) slot_[drawn_[k]] = k;
  const auto root = [&](std::uint32_t k) {
    while (group_[k] != k) k = group_[k] = group_[group_[k]];
    return k;
  };
  for (std::uint32_t k = 0; k < drawn_.size(); ++k) {
    const OccluderSet::Polygon& poly = set.polygons[drawn_[k]];
    for (std::uint32_t i = poly.edge_first; i < poly.edge_first + poly.edge_count; ++i)
      for (std::uint32_t n = 0; n < set.edges[i].partner_count; ++n) {
        const std::uint32_t q = set.partners[set.edges[i].partner_first + n];
        if (chosen_[q] == view_) group_[root(k)] = root(slot_[q]);
      }
  }
  order_.resize(drawn_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  for (std::uint32_t k = 0; k < drawn_.size(); ++k) group_[k] = root(k);
  std::sort(order_.begin(), order_.end(), [&](std::uint32_t x, std::uint32_t y) {
    return std::tie(group_[x], x) < std::tie(group_[y], y);
  });
  for (std::size_t n = 0; n < order_.size(); ++n) {
    if (n == 0 || group_[order_[n]] != group_[order_[n - 1]]) buffer_.begin_group();
    const OccluderSet::Polygon& poly = set.polygons[drawn_[order_[n]]];
    edges_.clear();
    for (std::uint32_t i = poly.edge_first; i < poly.edge_first + poly.edge_count; ++i) {
      const OccluderSet::Edge& edge = set.edges[i];
      bool open = true;
      for (std::uint32_t k = edge.partner_first; k < edge.partner_first + edge.partner_count && open; ++k)
        open = chosen_[set.partners[k]] != view_;
      edges_.push_back({edge.a, edge.b, open});
    }
    buffer_.add({set.corners.data() + poly.corner_first, poly.corner_count},
                {set.triangles.data() + poly.triangle_first, std::size_t(poly.triangle_count) * 3}, edges_);
    if (n + 1 == order_.size() || group_[order_[n + 1]] != group_[order_[n]]) buffer_.end_group();
  }
  occluders_ = drawn_.size();
  buffer_.finish();
  if (drawn_.empty()) return;
  for (const std::uint32_t u : candidates)
    if (u < layout.units() && buffer_.hides(layout.boxes[u])) {
      hidden_[u] = view_;
      ++hidden_count_;
    }
}

}  // namespace walk::render
