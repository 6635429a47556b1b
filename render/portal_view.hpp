#pragma once
// Per-frame portal culling on top of the PVS (Luebke & Georges 1995). From the eye's cell, each portal the
// compiler stored is projected to the screen and its rectangle cut down to the rectangle the cell is seen
// through; the cells reached, each with the rectangle it is seen through, bound what this view can show. A
// unit (cluster) is drawn only when its box touches a reached cell and its screen rectangle meets that
// cell's. Conservative: a sight line from the eye to a visible point passes the portals of its way, so the
// point's image lies in each portal's rectangle and in its own unit's. The PVS holds for any eye in the cell;
// this holds for the one eye and direction of the frame, so it draws what the eye's chains of portals show.
// Pure CPU.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"
#include "render/frustum.hpp"

namespace walk::render {

// A rectangle in normalised device coordinates; lo > hi: empty.
struct NdcRect {
  float lo[2] = {1.0f, 1.0f}, hi[2] = {-1.0f, -1.0f};
  [[nodiscard]] bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1]; }
  [[nodiscard]] bool meets(const NdcRect& o) const {
    return !empty() && !o.empty() && lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] &&
           o.lo[1] <= hi[1];
  }
};
[[nodiscard]] NdcRect whole_screen();
[[nodiscard]] NdcRect intersection(const NdcRect& a, const NdcRect& b);

// The screen rectangle of a flat convex polygon (corners in local coordinates), clipped to what lies in
// front of the eye; empty when none of it does.
[[nodiscard]] NdcRect project_polygon(std::span<const glm::vec3> corners, const glm::mat4& view_projection);
// The screen rectangle of a box: its corners' when all lie in front of the eye, the whole screen when some
// lie behind (the box reaches round the eye), empty when none is in front.
[[nodiscard]] NdcRect project_box(const Box& box, const glm::mat4& view_projection);

// Appends the cells `box` touches (or comes within a millimetre of), down the node tree.
void cells_touching(std::span<const model::NodeRecord> nodes, std::size_t cell_count, const Box& box,
                    std::vector<std::uint32_t>& out);

// The cells sight starts in, sorted: the eye's, and every cell the pyramid from the eye to the near plane
// touches. The near plane clips away a wall nearer than it, and shows what lies behind: from an eye a
// centimetre from a wall, the cells beyond it are seen as if the eye stood in them.
[[nodiscard]] std::vector<std::uint32_t> near_cells(std::span<const model::NodeRecord> nodes,
                                                    std::size_t cell_count, std::uint32_t eye_cell,
                                                    const glm::vec3& eye, const glm::mat4& view_projection);

class PortalView {
 public:
  // Load time: the portals and, down the node tree, the cells each unit's box touches.
  PortalView(std::span<const model::PortalRecord> portals, std::span<const model::NodeRecord> nodes,
             std::size_t cell_count, std::span<const Box> unit_boxes);

  // Per frame: the cells seen from `eye` (in `eye_cell`) through `view_projection`, and the rectangle each
  // is seen through. An eye cell out of range sees everything.
  void look(std::uint32_t eye_cell, const glm::vec3& eye, const glm::mat4& view_projection);
  // The same from `starts`, the near_cells() of the view, when the caller has them already. None, or one
  // out of range: everything is seen.
  void look_from(std::span<const std::uint32_t> starts, const glm::vec3& eye,
                 const glm::mat4& view_projection);
  // After look(): may unit `u` show in this frame?
  [[nodiscard]] bool shows(std::uint32_t u) const;

  [[nodiscard]] std::size_t cells_reached() const { return reached_.size(); }
  // This frame's near_cells(), each seen through the whole screen.
  [[nodiscard]] std::span<const std::uint32_t> start_cells() const { return start_; }
  // The rectangle `cell` is seen through in this frame (empty: not reached).
  [[nodiscard]] NdcRect seen_through(std::uint32_t cell) const {
    return cell < seen_through_.size() ? seen_through_[cell] : NdcRect{};
  }
  [[nodiscard]] std::size_t portals_passed() const { return passed_; }
  [[nodiscard]] bool sees_everything() const { return everything_; }
  [[nodiscard]] std::span<const std::uint32_t> unit_cells(std::uint32_t u) const {
    return {unit_cells_.data() + unit_first_[u], unit_first_[u + 1] - unit_first_[u]};
  }

 private:
  struct Way {
    std::uint32_t portal, to;
  };
  std::vector<model::PortalRecord> portals_;
  std::vector<model::NodeRecord> nodes_;
  std::vector<std::vector<Way>> ways_out_;  // per cell: the portals sight leaves it by, and where to
  std::vector<std::uint32_t> unit_first_, unit_cells_;
  std::vector<Box> unit_boxes_;
  // This frame's.
  glm::mat4 view_projection_{1.0f};
  std::vector<NdcRect> seen_through_;  // per cell; empty: not reached
  std::vector<std::uint32_t> reached_, start_;
  std::vector<NdcRect> portal_rects_;  // per portal: its screen rectangle, when projected_ == frame_
  std::vector<std::uint64_t> projected_;
  std::uint64_t frame_ = 0;
  std::size_t passed_ = 0;
  bool everything_ = true;
};

}  // namespace walk::render
