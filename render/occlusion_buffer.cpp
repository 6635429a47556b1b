#include "render/occlusion_buffer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

namespace walk::render {
namespace {

// Pixels grow by this much (buffer pixels) on every side when an edge or a box is placed on them: far above
// the double rounding here and llvmpipe's 1/256-pixel snapping of a full-size frame (a buffer pixel spans
// several), so a sample the GPU puts on the other side of an edge is still counted as crossed.
constexpr double kPixelSlack = 1e-2;
// A box is hidden only when the occluders lie nearer by more than this (window depth, 0..1): above the
// float rounding of the GPU's z / w and a few hundred steps of a 24-bit depth buffer, so an occluder and a
// surface just behind it never meet in a tie the GPU resolves the other way.
constexpr double kDepthSlack = 1e-5;
// A polygon whose largest triangle spans less than this on screen (buffer pixels squared, twice the area)
// is seen edge on: its depth plane is ill-conditioned and it covers nothing.
constexpr double kEdgeOnArea = 1e-3;
// Not covered: above every window depth.
constexpr float kUncovered = 2.0f;
// A box rectangle is tested on the pyramid level where it spans at most this many pixels a side.
constexpr int kProbeSpan = 8;

// Is the clip-space point in front of the near plane (z >= -w)?
bool beyond_near(const glm::dvec4& c) {
  return c.z + c.w >= 0.0;
}

// Where the segment from `inside` to `outside` crosses the near plane. Callers pass each shared edge's ends
// in one order, so both triangles of an edge get the same point.
glm::dvec4 near_crossing(const glm::dvec4& a, const glm::dvec4& b) {
  const double da = a.z + a.w, db = b.z + b.w;
  const double t = da / (da - db);
  return a + t * (b - a);
}

}  // namespace

void OcclusionBuffer::clear(const glm::mat4& view_projection, int width, int height, int columns) {
  matrix_ = glm::dmat4(view_projection);
  columns_ = std::max(1, columns);
  rows_ = std::max(
      1, int(std::lround(double(columns_) * double(std::max(1, height)) / double(std::max(1, width)))));
  const std::size_t n = std::size_t(columns_) * std::size_t(rows_);
  depth_.assign(n, 0.0f);
  centre_.assign(n, 0);
  open_.assign(n, 0);
  group_of_.assign(n, 0);
  group_ = 0;
  covered_.assign(n, kUncovered);
  pyramid_.clear();
  level_size_.clear();
}

void OcclusionBuffer::begin_group() {
  ++group_;
  touched_.clear();
}

void OcclusionBuffer::end_group() {
  for (const std::size_t i : touched_)
    if (centre_[i] && !open_[i]) covered_[i] = std::min(covered_[i], depth_[i]);
  touched_.clear();
}

std::size_t OcclusionBuffer::touch(int x, int y) {
  const std::size_t i = std::size_t(y) * std::size_t(columns_) + std::size_t(x);
  if (group_of_[i] != group_) {
    group_of_[i] = group_;
    depth_[i] = 0.0f;
    centre_[i] = 0;
    open_[i] = 0;
    touched_.push_back(i);
  }
  return i;
}

OcclusionBuffer::ScreenPoint OcclusionBuffer::project(const glm::dvec4& c) const {
  const double inv_w = 1.0 / c.w;
  return {(c.x * inv_w * 0.5 + 0.5) * columns_, (c.y * inv_w * 0.5 + 0.5) * rows_, c.z * inv_w * 0.5 + 0.5,
          inv_w};
}

float OcclusionBuffer::bound_over_pixel(int x, int y, const double plane[6]) const {
  // Affine over the pixel's square: the largest depth and the smallest 1/w are at corners.
  const double z = plane[0] * x + plane[1] * y + plane[2] + std::max(plane[0], 0.0) + std::max(plane[1], 0.0);
  const double inv_w =
      plane[3] * x + plane[4] * y + plane[5] + std::min(plane[3], 0.0) + std::min(plane[4], 0.0);
  if (!(inv_w > 0.0) || !(z < 1.0)) return kUncovered;  // the plane passes the eye or the far plane here
  return std::nextafter(float(z), kUncovered);          // rounded up
}

void OcclusionBuffer::mark_edge(const ScreenPoint& p, const ScreenPoint& q, bool open,
                                const double plane[6]) {
  const double y_lo = std::min(p.y, q.y) - kPixelSlack, y_hi = std::max(p.y, q.y) + kPixelSlack;
  const int r0 = std::max(0, int(std::floor(y_lo))), r1 = std::min(rows_ - 1, int(std::floor(y_hi)));
  const double dy = q.y - p.y;
  for (int r = r0; r <= r1; ++r) {
    // The segment's part within the row's band (grown by the slack), as x extent.
    double x_lo = std::min(p.x, q.x), x_hi = std::max(p.x, q.x);
    if (std::abs(dy) > 1e-12) {
      double t0 = (double(r) - kPixelSlack - p.y) / dy, t1 = (double(r + 1) + kPixelSlack - p.y) / dy;
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::clamp(t0, 0.0, 1.0);
      t1 = std::clamp(t1, 0.0, 1.0);
      const double xa = p.x + t0 * (q.x - p.x), xb = p.x + t1 * (q.x - p.x);
      x_lo = std::min(xa, xb);
      x_hi = std::max(xa, xb);
    }
    const int c0 = std::max(0, int(std::floor(x_lo - kPixelSlack)));
    const int c1 = std::min(columns_ - 1, int(std::floor(x_hi + kPixelSlack)));
    for (int c = c0; c <= c1; ++c) {
      const std::size_t i = touch(c, r);
      depth_[i] = std::max(depth_[i], bound_over_pixel(c, r, plane));
      if (open) open_[i] = 1;
    }
  }
}

void OcclusionBuffer::cover_triangle(const ScreenPoint& p, const ScreenPoint& q, const ScreenPoint& r,
                                     const double plane[6]) {
  const double area = (q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y);
  if (area == 0.0) return;
  const double s = area > 0.0 ? 1.0 : -1.0;
  const int r0 = std::max(0, int(std::floor(std::min({p.y, q.y, r.y}))));
  const int r1 = std::min(rows_ - 1, int(std::floor(std::max({p.y, q.y, r.y}))));
  const std::array<std::pair<const ScreenPoint*, const ScreenPoint*>, 3> edges{
      {{&p, &q}, {&q, &r}, {&r, &p}}};
  for (int y = r0; y <= r1; ++y) {
    // The centres of this row inside all three edges (inclusive: a centre on an edge counts; where that
    // edge is the group's boundary, the open edge crossing the pixel takes the pixel back out), as a span
    // of x: each edge function is linear in x along the row.
    const double cy = y + 0.5;
    double x_lo = 0.0, x_hi = double(columns_);
    for (const auto& [a, b] : edges) {
      const double m = -s * (b->y - a->y);
      const double k = s * ((b->x - a->x) * (cy - a->y) + (b->y - a->y) * a->x);
      if (m > 0.0)
        x_lo = std::max(x_lo, -k / m);
      else if (m < 0.0)
        x_hi = std::min(x_hi, -k / m);
      else if (k < 0.0)
        x_hi = -1.0;
    }
    const int c0 = std::max(0, int(std::ceil(x_lo - 0.5)));
    const int c1 = std::min(columns_ - 1, int(std::floor(x_hi - 0.5)));
    if (c0 > c1) continue;
    // The plane's bounds over each pixel's square along the row: affine, largest depth and smallest 1/w at
    // a corner.
    const double z_row = plane[1] * y + plane[2] + std::max(plane[0], 0.0) + std::max(plane[1], 0.0);
    const double w_row = plane[4] * y + plane[5] + std::min(plane[3], 0.0) + std::min(plane[4], 0.0);
    for (int x = c0; x <= c1; ++x) {
      const std::size_t i = touch(x, y);
      centre_[i] = 1;
      const double z = plane[0] * x + z_row, inv_w = plane[3] * x + w_row;
      // The float's rounding (below 1e-7) is far inside kDepthSlack.
      depth_[i] = std::max(depth_[i], inv_w > 0.0 && z < 1.0 ? float(z) : kUncovered);
    }
  }
}

void OcclusionBuffer::add(std::span<const glm::vec3> corners, std::span<const std::uint32_t> triangles,
                          std::span<const OccluderEdge> edges) {
  if (corners.empty() || triangles.size() < 3) return;
  std::vector<glm::dvec4> clip(corners.size());
  bool clipped = false;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    clip[i] = matrix_ * glm::dvec4(glm::dvec3(corners[i]), 1.0);
    if (clip[i].z > clip[i].w) return;  // past the far plane: not drawn there, so it hides nothing
    clipped = clipped || !beyond_near(clip[i]);
  }
  // Triangles after the near plane clips them, as points on the screen, and the near plane's cut through
  // each (an open edge: what lies beyond it is drawn).
  std::vector<std::array<ScreenPoint, 3>> pieces;
  std::vector<std::array<ScreenPoint, 2>> cuts;
  auto crossing = [&](std::uint32_t a, std::uint32_t b) {
    return project(a < b ? near_crossing(clip[a], clip[b]) : near_crossing(clip[b], clip[a]));
  };
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const std::uint32_t v[3] = {triangles[t], triangles[t + 1], triangles[t + 2]};
    if (v[0] >= corners.size() || v[1] >= corners.size() || v[2] >= corners.size()) continue;
    std::array<ScreenPoint, 4> kept;
    std::size_t n = 0;
    std::array<ScreenPoint, 2> cut;
    std::size_t cut_n = 0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      const bool in_a = beyond_near(clip[a]), in_b = beyond_near(clip[b]);
      if (in_a) kept[n++] = project(clip[a]);
      if (in_a != in_b) {
        kept[n++] = crossing(a, b);
        if (cut_n < 2) cut[cut_n++] = kept[n - 1];
      }
    }
    if (n >= 3) pieces.push_back({kept[0], kept[1], kept[2]});
    if (n == 4) pieces.push_back({kept[0], kept[2], kept[3]});
    if (cut_n == 2) cuts.push_back(cut);
  }
  if (pieces.empty()) return;
  // The depth plane of the largest piece, moved back until no corner lies behind it (and 1/w down until
  // none lies nearer): an upper bound of the polygon's depth wherever it is, flat or not quite.
  const auto* best = &pieces.front();
  double best_area = 0.0;
  for (const auto& piece : pieces) {
    const double a = std::abs((piece[1].x - piece[0].x) * (piece[2].y - piece[0].y) -
                              (piece[2].x - piece[0].x) * (piece[1].y - piece[0].y));
    if (a > best_area) {
      best_area = a;
      best = &piece;
    }
  }
  if (!(best_area > kEdgeOnArea)) return;
  const auto& [p0, p1, p2] = *best;
  const double det = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
  double plane[6];
  for (int k = 0; k < 2; ++k) {
    auto value = [k](const ScreenPoint& p) { return k == 0 ? p.z : p.inv_w; };
    const double v0 = value(p0), v1 = value(p1), v2 = value(p2);
    const double a = ((v1 - v0) * (p2.y - p0.y) - (v2 - v0) * (p1.y - p0.y)) / det;
    const double b = ((p1.x - p0.x) * (v2 - v0) - (p2.x - p0.x) * (v1 - v0)) / det;
    plane[3 * k] = a;
    plane[3 * k + 1] = b;
    plane[3 * k + 2] = v0 - a * p0.x - b * p0.y;
  }
  for (const auto& piece : pieces)
    for (const ScreenPoint& p : piece) {
      plane[2] = std::max(plane[2], p.z - plane[0] * p.x - plane[1] * p.y);
      plane[5] = std::min(plane[5], p.inv_w - plane[3] * p.x - plane[4] * p.y);
    }

  for (const auto& piece : pieces) cover_triangle(piece[0], piece[1], piece[2], plane);
  for (const OccluderEdge& e : edges) {
    if (e.a >= corners.size() || e.b >= corners.size()) continue;
    const bool in_a = beyond_near(clip[e.a]), in_b = beyond_near(clip[e.b]);
    if (!in_a && !in_b) continue;
    const ScreenPoint pa = in_a ? project(clip[e.a]) : crossing(e.a, e.b);
    const ScreenPoint pb = in_b ? project(clip[e.b]) : crossing(e.a, e.b);
    mark_edge(pa, pb, e.open, plane);
  }
  if (clipped)
    for (const auto& cut : cuts) mark_edge(cut[0], cut[1], true, plane);
}

void OcclusionBuffer::finish() {
  pyramid_.assign(1, covered_);
  level_size_.assign(1, {columns_, rows_});
  while (level_size_.back().first > 1 || level_size_.back().second > 1) {
    const auto [w, h] = level_size_.back();
    const int nw = (w + 1) / 2, nh = (h + 1) / 2;
    std::vector<float> next(std::size_t(nw) * std::size_t(nh), 0.0f);
    const auto& below = pyramid_.back();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        float& up = next[std::size_t(y / 2) * std::size_t(nw) + std::size_t(x / 2)];
        up = std::max(up, below[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
      }
    pyramid_.push_back(std::move(next));
    level_size_.push_back({nw, nh});
  }
}

bool OcclusionBuffer::hides(const Box& box) const {
  if (box.empty() || pyramid_.empty()) return false;
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300, z_near = 1e300;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec4 c = matrix_ * glm::dvec4(box.lo[0] + (k & 1 ? box.hi[0] - box.lo[0] : 0.0f),
                                              box.lo[1] + (k & 2 ? box.hi[1] - box.lo[1] : 0.0f),
                                              box.lo[2] + (k & 4 ? box.hi[2] - box.lo[2] : 0.0f), 1.0);
    if (!beyond_near(c) || !(c.w > 0.0)) return false;  // reaches round the eye
    const ScreenPoint p = project(c);
    x_lo = std::min(x_lo, p.x);
    x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
    z_near = std::min(z_near, p.z);
  }
  if (x_hi < 0.0 || y_hi < 0.0 || x_lo > columns_ || y_lo > rows_) return false;  // the frustum's call
  int c0 = std::max(0, int(std::floor(x_lo - kPixelSlack)));
  int c1 = std::min(columns_ - 1, int(std::floor(x_hi + kPixelSlack)));
  int r0 = std::max(0, int(std::floor(y_lo - kPixelSlack)));
  int r1 = std::min(rows_ - 1, int(std::floor(y_hi + kPixelSlack)));
  std::size_t level = 0;
  while (level + 1 < pyramid_.size() && (c1 - c0 >= kProbeSpan || r1 - r0 >= kProbeSpan)) {
    c0 /= 2;
    c1 /= 2;
    r0 /= 2;
    r1 /= 2;
    ++level;
  }
  const int w = level_size_[level].first;
  const double limit = z_near - kDepthSlack;
  for (int y = r0; y <= r1; ++y)
    for (int x = c0; x <= c1; ++x)
      if (!(double(pyramid_[level][std::size_t(y) * std::size_t(w) + std::size_t(x)]) < limit)) return false;
  return true;
}

std::size_t OcclusionBuffer::covered_pixels() const {
  if (pyramid_.empty()) return 0;
  return std::size_t(
      std::count_if(pyramid_[0].begin(), pyramid_[0].end(), [](float d) { return d <= 1.0f; }));
}

float OcclusionBuffer::depth_at(int column, int row) const {
  if (pyramid_.empty() || column < 0 || row < 0 || column >= columns_ || row >= rows_) return kUncovered;
  return pyramid_[0][std::size_t(row) * std::size_t(columns_) + std::size_t(column)];
}

}  // namespace walk::render
