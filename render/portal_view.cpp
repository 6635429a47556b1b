#include "render/portal_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

namespace walk::render {
namespace {

// Clip-space w is the distance in front of the eye along the view axis, in metres. Portals are clipped to
// w >= kMinClipW before projection: far below any near plane (View::near_plane, 5 cm by default), so no
// drawn point is lost, and far enough above zero that the projection stays finite.
constexpr float kMinClipW = 1e-6f;
// Rectangles grow by this much of normalised device coordinates on every side before they are compared:
// about 1/20 of a pixel across at 4K, above the float rounding in which the GPU and this code differ.
constexpr float kNdcSlack = 1e-4f;
// An eye this close to a portal's plane (metres) sees the portal edge on: its projection degenerates to a
// line, yet every direction into the next cell passes it; the cell is seen through the whole rectangle.
constexpr float kOnPortalPlane = 1e-4f;
// A box within this distance of a splitting plane (metres) touches the cells on both sides: walls lie in
// the planes that bound cells, and float rounding of local coordinates up to 8 km is below 1 mm.
constexpr double kCellTouchSlack = 1e-3;
// Portal passes one frame may spend; past it (a maze of cells seen through one another) the frame draws its
// cell's whole PVS, as without portal culling. Each pass is a few hundred flops.
constexpr std::size_t kMaxPortalPasses = 1 << 16;
constexpr std::size_t kMaxPolygonCorners = 8;

void grow(NdcRect& r, float x, float y) {
  r.lo[0] = std::min(r.lo[0], x);
  r.lo[1] = std::min(r.lo[1], y);
  r.hi[0] = std::max(r.hi[0], x);
  r.hi[1] = std::max(r.hi[1], y);
}

NdcRect grown(NdcRect r) {
  if (r.empty()) return r;
  for (int k = 0; k < 2; ++k) {
    r.lo[k] -= kNdcSlack;
    r.hi[k] += kNdcSlack;
  }
  return r;
}

NdcRect bounding(const NdcRect& a, const NdcRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  NdcRect r;
  for (int k = 0; k < 2; ++k) {
    r.lo[k] = std::min(a.lo[k], b.lo[k]);
    r.hi[k] = std::max(a.hi[k], b.hi[k]);
  }
  return r;
}

bool contains(const NdcRect& outer, const NdcRect& inner) {
  return inner.empty() || (!outer.empty() && outer.lo[0] <= inner.lo[0] && outer.lo[1] <= inner.lo[1] &&
                           outer.hi[0] >= inner.hi[0] && outer.hi[1] >= inner.hi[1]);
}

// The four corners of a portal's box in its plane (the box is flat on its axis up to rounding).
std::array<glm::vec3, 4> portal_corners(const model::PortalRecord& p) {
  const int axis = int(p.flags & model::kPortalAxisMask);
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const float coord = 0.5f * (p.bounds_min[axis] + p.bounds_max[axis]);
  std::array<glm::vec3, 4> corners;
  const float us[4] = {p.bounds_min[u], p.bounds_max[u], p.bounds_max[u], p.bounds_min[u]};
  const float vs[4] = {p.bounds_min[v], p.bounds_min[v], p.bounds_max[v], p.bounds_max[v]};
  for (int i = 0; i < 4; ++i) {
    corners[std::size_t(i)][axis] = coord;
    corners[std::size_t(i)][u] = us[i];
    corners[std::size_t(i)][v] = vs[i];
  }
  return corners;
}

}  // namespace

NdcRect whole_screen() {
  return NdcRect{{-1.0f, -1.0f}, {1.0f, 1.0f}};
}

NdcRect intersection(const NdcRect& a, const NdcRect& b) {
  NdcRect r;
  for (int k = 0; k < 2; ++k) {
    r.lo[k] = std::max(a.lo[k], b.lo[k]);
    r.hi[k] = std::min(a.hi[k], b.hi[k]);
  }
  return r;
}

NdcRect project_polygon(std::span<const glm::vec3> corners, const glm::mat4& view_projection) {
  // Sutherland-Hodgman against w = kMinClipW in clip space, then the corners' rectangle. Portals have four
  // corners; a polygon with more than the buffer holds is taken as filling the screen (conservative).
  std::array<glm::vec4, kMaxPolygonCorners> clip;
  if (corners.size() > clip.size()) return whole_screen();
  const std::size_t n = corners.size();
  for (std::size_t i = 0; i < n; ++i) clip[i] = view_projection * glm::vec4(corners[i], 1.0f);
  NdcRect r;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec4& a = clip[i];
    const glm::vec4& b = clip[(i + 1) % n];
    const bool a_in = a.w >= kMinClipW, b_in = b.w >= kMinClipW;
    if (a_in) grow(r, a.x / a.w, a.y / a.w);
    if (a_in != b_in) {
      const float t = (kMinClipW - a.w) / (b.w - a.w);
      const glm::vec4 p = a + (b - a) * t;
      grow(r, p.x / kMinClipW, p.y / kMinClipW);
    }
  }
  return grown(r);
}

NdcRect project_box(const Box& box, const glm::mat4& view_projection) {
  NdcRect r;
  if (box.empty()) return r;
  int behind = 0;
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 c = view_projection * glm::vec4(box.lo[0] + (i & 1 ? box.hi[0] - box.lo[0] : 0.0f),
                                                    box.lo[1] + (i & 2 ? box.hi[1] - box.lo[1] : 0.0f),
                                                    box.lo[2] + (i & 4 ? box.hi[2] - box.lo[2] : 0.0f), 1.0f);
    if (c.w < kMinClipW) {
      ++behind;
      continue;
    }
    grow(r, c.x / c.w, c.y / c.w);
  }
  if (behind == 8) return NdcRect{};
  return behind > 0 ? whole_screen() : grown(r);
}

PortalView::PortalView(std::span<const model::PortalRecord> portals, std::span<const model::NodeRecord> nodes,
                       std::size_t cell_count, std::span<const Box> unit_boxes)
    : portals_(portals.begin(), portals.end()),
      nodes_(nodes.begin(), nodes.end()),
      ways_out_(cell_count),
      unit_boxes_(unit_boxes.begin(), unit_boxes.end()),
      seen_through_(cell_count),
      portal_rects_(portals.size()),
      projected_(portals.size(), 0) {
  for (std::uint32_t i = 0; i < portals_.size(); ++i) {
    const auto& p = portals_[i];
    if (p.back >= cell_count || p.front >= cell_count) continue;
    if (p.flags & model::kPortalForward) ways_out_[p.back].push_back({i, p.front});
    if (p.flags & model::kPortalBackward) ways_out_[p.front].push_back({i, p.back});
  }
  // Each unit's cells, down the tree.
  unit_first_.reserve(unit_boxes.size() + 1);
  unit_first_.push_back(0);
  for (const Box& box : unit_boxes) {
    cells_touching(nodes_, cell_count, box, unit_cells_);
    unit_first_.push_back(std::uint32_t(unit_cells_.size()));
  }
}

void cells_touching(std::span<const model::NodeRecord> nodes, std::size_t cell_count, const Box& box,
                    std::vector<std::uint32_t>& out) {
  // Down the tree: a box goes to every side of a plane it comes within the slack of.
  if (box.empty() || cell_count == 0) return;
  if (nodes.empty()) {
    out.push_back(0);
    return;
  }
  std::vector<std::int32_t> stack{0};
  while (!stack.empty()) {
    const std::int32_t node = stack.back();
    stack.pop_back();
    if (node < 0) {
      const auto cell = std::uint32_t(-node - 1);
      if (cell < cell_count) out.push_back(cell);
      continue;
    }
    if (std::size_t(node) >= nodes.size()) continue;
    const auto& n = nodes[std::size_t(node)];
    double centre = n.plane[3], reach = 0.0;
    for (int k = 0; k < 3; ++k) {
      centre += n.plane[k] * 0.5 * (double(box.lo[k]) + double(box.hi[k]));
      reach += std::abs(n.plane[k]) * 0.5 * (double(box.hi[k]) - double(box.lo[k]));
    }
    if (centre + reach >= -kCellTouchSlack) stack.push_back(n.front);
    if (centre - reach < kCellTouchSlack) stack.push_back(n.back);
  }
}

std::vector<std::uint32_t> near_cells(std::span<const model::NodeRecord> nodes, std::size_t cell_count,
                                      std::uint32_t eye_cell, const glm::vec3& eye,
                                      const glm::mat4& view_projection) {
  std::vector<std::uint32_t> cells{eye_cell};
  const glm::mat4 to_local = glm::inverse(view_projection);
  Box near = empty_box();
  const float eye_point[3] = {eye.x, eye.y, eye.z};
  grow(near, eye_point);
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f}) {
      const glm::vec4 p = to_local * glm::vec4(x, y, -1.0f, 1.0f);  // a corner of the near rectangle
      const float corner[3] = {p.x / p.w, p.y / p.w, p.z / p.w};
      if (std::isfinite(corner[0]) && std::isfinite(corner[1]) && std::isfinite(corner[2]))
        grow(near, corner);
    }
  cells_touching(nodes, cell_count, near, cells);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

void PortalView::look(std::uint32_t eye_cell, const glm::vec3& eye, const glm::mat4& view_projection) {
  if (eye_cell >= seen_through_.size()) {
    look_from({}, eye, view_projection);
    return;
  }
  look_from(near_cells(nodes_, seen_through_.size(), eye_cell, eye, view_projection), eye, view_projection);
}

void PortalView::look_from(std::span<const std::uint32_t> starts, const glm::vec3& eye,
                           const glm::mat4& view_projection) {
  for (const std::uint32_t c : reached_) seen_through_[c] = NdcRect{};
  reached_.clear();
  start_.assign(starts.begin(), starts.end());
  passed_ = 0;
  everything_ = starts.empty() || std::any_of(starts.begin(), starts.end(),
                                              [&](std::uint32_t c) { return c >= seen_through_.size(); });
  if (everything_) return;
  view_projection_ = view_projection;
  ++frame_;
  std::vector<std::uint32_t> work = start_;
  for (const std::uint32_t cell : work) {
    if (seen_through_[cell].empty()) reached_.push_back(cell);
    seen_through_[cell] = whole_screen();
  }
  // Each cell is walked again whenever the rectangle it is seen through grows; rectangles only grow, so
  // the walk ends, and each cell's is the bounding rectangle of every way the eye sees into it.
  while (!work.empty()) {
    const std::uint32_t cell = work.back();
    work.pop_back();
    for (const Way& way : ways_out_[cell]) {
      if (++passed_ > kMaxPortalPasses) {
        everything_ = true;
        return;
      }
      const NdcRect from = seen_through_[cell];
      const auto& p = portals_[way.portal];
      const int axis = int(p.flags & model::kPortalAxisMask);
      const float coord = 0.5f * (p.bounds_min[axis] + p.bounds_max[axis]);
      NdcRect through = from;
      if (std::abs(eye[axis] - coord) > kOnPortalPlane) {
        // Each portal is projected once a frame, however often the walk passes it.
        if (projected_[way.portal] != frame_) {
          projected_[way.portal] = frame_;
          portal_rects_[way.portal] = project_polygon(portal_corners(p), view_projection);
        }
        through = intersection(from, portal_rects_[way.portal]);
      }
      if (through.empty()) continue;
      NdcRect& seen = seen_through_[way.to];
      if (contains(seen, through)) continue;
      if (seen.empty()) reached_.push_back(way.to);
      seen = bounding(seen, through);
      work.push_back(way.to);
    }
  }
}

bool PortalView::shows(std::uint32_t u) const {
  if (everything_) return true;
  if (u + 1 >= unit_first_.size()) return true;  // not a unit this view knows: never drop it
  bool touches_reached = false;
  for (const std::uint32_t c : unit_cells(u)) touches_reached |= !seen_through_[c].empty();
  if (!touches_reached) return false;
  const NdcRect box = project_box(unit_boxes_[u], view_projection_);
  for (const std::uint32_t c : unit_cells(u))
    if (seen_through_[c].meets(box)) return true;
  return false;
}

}  // namespace walk::render
