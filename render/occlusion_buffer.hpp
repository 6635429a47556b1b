#pragma once
// A small software depth buffer of the nearest large opaque polygons (occluders), against which cluster boxes
// are tested before they are drawn: occlusion culling after the PVS, the frustum and the portal walk, for
// what lies behind the walls round the doors the walk sees through (Greene, Kass & Miller 1993's depth
// pyramid, filled with a few occluders as in Zhang et al. 1997).
//
// Conservative in continuous screen space, so a hidden box changes no pixel at any resolution or jitter.
// Occluders come in groups, each one surface (polygons joined at shared edges: a room's walls, floor and
// ceiling). A buffer pixel is covered by a group when the group covers its whole square (its centre lies
// in one of the group's polygons and no open edge of the group crosses it), with an upper bound of the
// group's depth over the square (a plane's depth is affine in screen space: its largest value is at a
// corner); the pixel keeps the nearest bound of the groups that cover it. A box is hidden only when every
// pixel its screen rectangle touches is covered nearer than the box's nearest corner, by more than the
// depth buffer's resolution. Pure CPU.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "render/frustum.hpp"

namespace walk::render {

// One boundary edge of an occluder polygon, between two of its corners. Open: nothing drawn this frame
// continues the surface across it (a wall's end, a door's jamb), so the pixels it crosses are not covered.
struct OccluderEdge {
  std::uint32_t a = 0, b = 0;
  bool open = true;
};

class OcclusionBuffer {
 public:
  // Starts an empty buffer of about `columns` pixels across, in the aspect of `width` x `height`, for the
  // view `view_projection` (the frame's own matrix, jitter included).
  void clear(const glm::mat4& view_projection, int width, int height, int columns);
  // A group of polygons that together make one surface: add() its polygons between these.
  void begin_group();
  void end_group();
  // Rasterises one flat opaque polygon of the open group: `triangles` (3 corner ids each) and its boundary
  // `edges`. A polygon seen edge on adds nothing; one reaching past the far plane adds nothing; the near
  // plane clips it (its cut is an open edge).
  void add(std::span<const glm::vec3> corners, std::span<const std::uint32_t> triangles,
           std::span<const OccluderEdge> edges);
  // Builds the depth pyramid; call after the last add() and before hides().
  void finish();
  // Is every point of `box` behind this frame's occluders? False for a box reaching in front of the near
  // plane or wholly off the screen.
  [[nodiscard]] bool hides(const Box& box) const;

  [[nodiscard]] int columns() const { return columns_; }
  [[nodiscard]] int rows() const { return rows_; }
  // Pixels covered by the occluders (after finish()): for tests and the bench.
  [[nodiscard]] std::size_t covered_pixels() const;
  // The depth (window z, 0..1 as the depth buffer holds it) a covered pixel is bounded by; above 1:
  // not covered.
  [[nodiscard]] float depth_at(int column, int row) const;

 private:
  struct ScreenPoint {
    double x = 0.0, y = 0.0;  // buffer pixels, row 0 at the bottom
    double z = 0.0;           // window depth
    double inv_w = 0.0;
  };
  [[nodiscard]] ScreenPoint project(const glm::dvec4& clip) const;
  void mark_edge(const ScreenPoint& p, const ScreenPoint& q, bool open, const double plane[6]);
  void cover_triangle(const ScreenPoint& p, const ScreenPoint& q, const ScreenPoint& r,
                      const double plane[6]);
  [[nodiscard]] float bound_over_pixel(int x, int y, const double plane[6]) const;

  glm::dmat4 matrix_{1.0};
  int columns_ = 0, rows_ = 0;
  [[nodiscard]] std::size_t touch(int x, int y);
  // Per pixel, for the open group (valid where `group_of_` is the group's number): the largest bound of its
  // polygons that touch the pixel, whether its centre lies in one, whether an open edge crosses it.
  std::vector<float> depth_;
  std::vector<std::uint8_t> centre_, open_;
  std::vector<std::uint32_t> group_of_;
  std::vector<std::size_t> touched_;  // pixels the open group touched
  std::uint32_t group_ = 0;
  std::vector<float> covered_;  // per pixel: the nearest bound of the groups covering it, else above 1
  // Level 0: `covered_`; level k + 1: the largest of 2 x 2 of level k.
  std::vector<std::vector<float>> pyramid_;
  std::vector<std::pair<int, int>> level_size_;
};

}  // namespace walk::render
