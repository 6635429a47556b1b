#include "firmware-host/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "model/model.hpp"

namespace walk::kiosk {
namespace {

constexpr double kUpFacing = 0.5;    // cos 60°: steeper surfaces are walls, not floors
constexpr double kInsideEps = 1e-7;  // barycentric slack so seams between floor triangles hold the walker
constexpr int kMaxResolvePasses = 8;
constexpr int kMaxGridCells = 512;  // per axis, bounds the grid's memory on huge sites

bool is_solid(std::uint32_t role) {
  return role == static_cast<std::uint32_t>(model::Role::Opaque) ||
         role == static_cast<std::uint32_t>(model::Role::Glass);
}

double cross2(const glm::dvec2& a, const glm::dvec2& b) {
  return a.x * b.y - a.y * b.x;
}

glm::dvec2 closest_on_segment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return a + ab * t;
}

// Sutherland-Hodgman against z >= lo (keep_above) or z <= hi: the part of a triangle inside the body's band.
std::vector<glm::dvec3> clip_z(const std::vector<glm::dvec3>& in, double z, bool keep_above) {
  std::vector<glm::dvec3> out;
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3& a = in[i];
    const glm::dvec3& b = in[(i + 1) % n];
    const bool a_in = keep_above ? a.z >= z : a.z <= z;
    const bool b_in = keep_above ? b.z >= z : b.z <= z;
    if (a_in) out.push_back(a);
    if (a_in != b_in) out.push_back(a + (b - a) * ((z - a.z) / (b.z - a.z)));
  }
  return out;
}

}  // namespace

Navigator::Navigator(const NavGeometry& geometry, const NavSettings& settings) : settings_(settings) {
  for (std::uint32_t pi = 0; pi < geometry.polygons.size(); ++pi) {
    const auto& poly = geometry.polygons[pi];
    if (!is_solid(poly.role))
      continue;  // Opening faces are holes; luminaires and ignored faces are not walls
    for (std::uint32_t k = 0; k + 2 < poly.index_count; k += 3) {
      Triangle t{};
      const auto* idx = &geometry.indices[poly.first_index + k];
      const auto& va = geometry.vertices[idx[0]];
      t.a = {va.position[0], va.position[1], va.position[2]};
      t.b = {geometry.vertices[idx[1]].position[0], geometry.vertices[idx[1]].position[1],
             geometry.vertices[idx[1]].position[2]};
      t.c = {geometry.vertices[idx[2]].position[0], geometry.vertices[idx[2]].position[1],
             geometry.vertices[idx[2]].position[2]};
      glm::dvec3 n = glm::cross(t.b - t.a, t.c - t.a);
      const double len = glm::length(n);
      if (len < 1e-12) continue;  // degenerate
      n /= len;
      // Triangulation may wind either way; the stored normal says which side the face looks to.
      const glm::dvec3 stored{va.normal[0], va.normal[1], va.normal[2]};
      if (glm::dot(n, stored) < 0.0) n = -n;
      t.z_min = std::min({t.a.z, t.b.z, t.c.z});
      t.z_max = std::max({t.a.z, t.b.z, t.c.z});
      t.lo = {std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y})};
      t.hi = {std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y})};
      t.polygon = pi;
      // Every solid triangle can block (a slab at chest height does); only up-facing ones carry the walker.
      walls_.push_back(t);
      if (n.z > kUpFacing) floors_.push_back(t);
    }
  }
  build_grid();
}

void Navigator::build_grid() {
  glm::dvec2 lo{1e300}, hi{-1e300};
  for (const auto& t : walls_) {
    lo = glm::min(lo, t.lo);
    hi = glm::max(hi, t.hi);
  }
  if (walls_.empty()) lo = hi = glm::dvec2(0.0);
  const glm::dvec2 size = hi - lo;
  cell_ = std::max({0.5, size.x / kMaxGridCells, size.y / kMaxGridCells});
  grid_origin_ = lo;
  nx_ = std::max(1, static_cast<int>(std::ceil(size.x / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil(size.y / cell_)) + 1);
  auto fill_grid = [&](const std::vector<Triangle>& tris, std::vector<std::vector<std::uint32_t>>& grid) {
    grid.assign(static_cast<std::size_t>(nx_) * ny_, {});
    for (std::uint32_t i = 0; i < tris.size(); ++i) {
      const int x0 = std::clamp(static_cast<int>((tris[i].lo.x - grid_origin_.x) / cell_), 0, nx_ - 1);
      const int x1 = std::clamp(static_cast<int>((tris[i].hi.x - grid_origin_.x) / cell_), 0, nx_ - 1);
      const int y0 = std::clamp(static_cast<int>((tris[i].lo.y - grid_origin_.y) / cell_), 0, ny_ - 1);
      const int y1 = std::clamp(static_cast<int>((tris[i].hi.y - grid_origin_.y) / cell_), 0, ny_ - 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) grid[static_cast<std::size_t>(y) * nx_ + x].push_back(i);
    }
  };
  fill_grid(walls_, wall_grid_);
  fill_grid(floors_, floor_grid_);
  stamp_.assign(std::max(walls_.size(), floors_.size()), 0);
}

template <typename F>
void Navigator::for_cells(const glm::dvec2& lo, const glm::dvec2& hi,
                          const std::vector<std::vector<std::uint32_t>>& grid, F&& f) const {
  const int x0 = static_cast<int>(std::floor((lo.x - grid_origin_.x) / cell_));
  const int x1 = static_cast<int>(std::floor((hi.x - grid_origin_.x) / cell_));
  const int y0 = static_cast<int>(std::floor((lo.y - grid_origin_.y) / cell_));
  const int y1 = static_cast<int>(std::floor((hi.y - grid_origin_.y) / cell_));
  if (x1 < 0 || y1 < 0 || x0 >= nx_ || y0 >= ny_) return;
  if (++stamp_value_ == 0) {  // wrapped: clear so old stamps cannot alias
    std::fill(stamp_.begin(), stamp_.end(), 0);
    stamp_value_ = 1;
  }
  for (int y = std::max(y0, 0); y <= std::min(y1, ny_ - 1); ++y)
    for (int x = std::max(x0, 0); x <= std::min(x1, nx_ - 1); ++x)
      for (std::uint32_t i : grid[static_cast<std::size_t>(y) * nx_ + x]) {
        if (stamp_[i] == stamp_value_) continue;
        stamp_[i] = stamp_value_;
        f(i);
      }
}

std::optional<FloorHit> Navigator::floor_at(const glm::dvec2& p, double max_z) const {
  std::optional<FloorHit> best;
  for_cells(p, p, floor_grid_, [&](std::uint32_t i) {
    const Triangle& t = floors_[i];
    if (p.x < t.lo.x || p.x > t.hi.x || p.y < t.lo.y || p.y > t.hi.y || t.z_min > max_z + 1e-6) return;
    const glm::dvec2 a{t.a}, b{t.b}, c{t.c};
    const double area = cross2(b - a, c - a);
    if (std::abs(area) < 1e-12) return;
    const double u = cross2(c - b, p - b) / area;  // weight of a
    const double v = cross2(a - c, p - c) / area;  // weight of b
    const double w = 1.0 - u - v;
    if (u < -kInsideEps || v < -kInsideEps || w < -kInsideEps) return;
    const double z = u * t.a.z + v * t.b.z + w * t.c.z;
    if (z > max_z + 1e-6) return;
    if (!best || z > best->z) best = FloorHit{z, t.polygon};
  });
  return best;
}

std::optional<Navigator::Contact> Navigator::contact(const Triangle& t, const glm::dvec2& p, double band_lo,
                                                     double band_hi) const {
  const double r = settings_.body_radius;
  if (t.z_max < band_lo || t.z_min > band_hi) return std::nullopt;
  if (p.x + r < t.lo.x || p.x - r > t.hi.x || p.y + r < t.lo.y || p.y - r > t.hi.y) return std::nullopt;
  auto clipped = clip_z(clip_z({t.a, t.b, t.c}, band_lo, true), band_hi, false);
  if (clipped.empty()) return std::nullopt;

  // Closest point on the band slice's 2D outline; a vertical wall projects to a segment.
  double best = 1e300;
  glm::dvec2 closest{0.0}, edge_dir{1.0, 0.0};
  double area = 0.0;
  bool left = true, right = true;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const glm::dvec2 a{clipped[i]}, b{clipped[(i + 1) % clipped.size()]};
    const glm::dvec2 q = closest_on_segment(p, a, b);
    const double d = glm::length(p - q);
    if (d < best) {
      best = d;
      closest = q;
      if (glm::length(b - a) > 1e-12) edge_dir = glm::normalize(b - a);
    }
    area += cross2(a, b);
    const double side = cross2(b - a, p - a);
    left = left && side >= 0.0;
    right = right && side <= 0.0;
  }
  const bool inside = std::abs(area) > 1e-9 && (left || right);
  Contact c;
  if (inside) {
    // The centre is over a slab in the band (a table top, a low ceiling): leave by the nearest edge.
    c.depth = best + r;
    c.normal = best > 1e-12 ? (closest - p) / best : glm::dvec2(-edge_dir.y, edge_dir.x);
    return c;
  }
  if (best >= r) return std::nullopt;
  c.depth = r - best;
  c.normal = best > 1e-12 ? (p - closest) / best : glm::dvec2(-edge_dir.y, edge_dir.x);
  return c;
}

double Navigator::penetration(const glm::dvec2& p, double floor_z) const {
  const double lo = floor_z + settings_.step_height, hi = floor_z + settings_.head_height;
  const glm::dvec2 r{settings_.body_radius};
  double deepest = 0.0;
  for_cells(p - r, p + r, wall_grid_, [&](std::uint32_t i) {
    if (auto c = contact(walls_[i], p, lo, hi)) deepest = std::max(deepest, c->depth);
  });
  return deepest;
}

bool Navigator::resolve(glm::dvec2& p, double floor_z) const {
  const double lo = floor_z + settings_.step_height, hi = floor_z + settings_.head_height;
  // Gather once with a margin for the pushes, then push out triangle by triangle until nothing overlaps.
  const glm::dvec2 reach{settings_.body_radius * 2.0 + settings_.max_substep};
  std::vector<std::uint32_t> near;
  for_cells(p - reach, p + reach, wall_grid_, [&](std::uint32_t i) {
    const Triangle& t = walls_[i];
    if (t.z_max >= lo && t.z_min <= hi) near.push_back(i);
  });
  constexpr double kSkin = 1e-6;  // leave a hair of space so the next test does not touch again
  for (int pass = 0; pass < kMaxResolvePasses; ++pass) {
    bool moved = false;
    for (std::uint32_t i : near) {
      if (auto c = contact(walls_[i], p, lo, hi); c && c->depth > kSkin) {
        p += c->normal * (c->depth + kSkin);
        moved = true;
      }
    }
    if (!moved) return true;
  }
  return penetration(p, floor_z) <= 1e-4;  // wedged in a corner the passes could not settle
}

bool Navigator::substep(const glm::dvec2& delta) {
  const glm::dvec2 from{feet_};
  glm::dvec2 p = from + delta;
  if (!resolve(p, feet_.z)) return false;
  // A wall push larger than the step means we were flung sideways through something; refuse it.
  if (glm::length(p - from) > glm::length(delta) + settings_.body_radius) return false;
  const auto floor = floor_at(p, feet_.z + settings_.step_height);
  if (!floor) return false;  // no floor: the edge of the building
  if (std::abs(floor->z - feet_.z) > 1e-9 && penetration(p, floor->z) > 1e-4) return false;
  distance_ += glm::length(p - from);
  feet_ = {p, floor->z};
  floor_polygon_ = floor->polygon;
  return true;
}

void Navigator::move(const glm::dvec2& delta) {
  const double len = glm::length(delta);
  if (len <= 0.0 || floor_polygon_ == kNoPolygon) return;
  const int steps = std::max(1, static_cast<int>(std::ceil(len / settings_.max_substep)));
  const glm::dvec2 piece = delta / static_cast<double>(steps);
  for (int i = 0; i < steps; ++i)
    if (!substep(piece)) return;
}

void Navigator::walk(double speed, double heading, double dt) {
  move(glm::dvec2(std::cos(heading), std::sin(heading)) * (speed * dt));
}

bool Navigator::place(const glm::dvec3& feet) {
  const glm::dvec2 p{feet};
  const auto floor = floor_at(p, feet.z + settings_.step_height);
  if (!floor || penetration(p, floor->z) > 1e-4) return false;
  feet_ = start_ = {p, floor->z};
  floor_polygon_ = start_polygon_ = floor->polygon;
  return true;
}

void Navigator::return_to_start() {
  feet_ = start_;
  floor_polygon_ = start_polygon_;
}

}  // namespace walk::kiosk
