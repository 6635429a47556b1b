#include "compiler/geometry/vis_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace walk::compiler {

bool Box::contains(const model::Vec3& p, double tol) const {
  for (int a = 0; a < 3; ++a)
    if (p[a] < min[a] - tol || p[a] > max[a] + tol) return false;
  return true;
}

bool Box::overlaps(const Box& o, double tol) const {
  for (int a = 0; a < 3; ++a)
    if (o.max[a] < min[a] - tol || o.min[a] > max[a] + tol) return false;
  return true;
}

Plane axial_plane(int axis, double coord, double sign) {
  Plane p;
  p.n = model::Vec3{0.0};
  p.n[axis] = sign > 0.0 ? 1.0 : -1.0;
  p.d = -p.n[axis] * coord;
  return p;
}

namespace {

// The windings the visibility stages clip have a few corners: their distances live on the stack below this
// many, since the portal flow and the proofs clip tens of millions of times and a heap block each time
// cost them about a tenth of their time (M building).
constexpr std::size_t kInlineCorners = 32;

bool wholly_in_front(const Winding& w, const Plane& p) {
  return std::all_of(w.begin(), w.end(),
                     [&](const model::Vec3& v) { return p.distance(v) >= -kPlaneEpsilon; });
}

}  // namespace

Winding clip_front(const Winding& w, const Plane& p) {
  if (w.empty()) return {};
  std::array<double, kInlineCorners> inline_d;
  std::vector<double> heap_d;
  double* d = inline_d.data();
  if (w.size() > kInlineCorners) {
    heap_d.resize(w.size());
    d = heap_d.data();
  }
  bool any_back = false, any_front = false;
  for (std::size_t i = 0; i < w.size(); ++i) {
    d[i] = p.distance(w[i]);
    if (d[i] < -kPlaneEpsilon) any_back = true;
    if (d[i] > kPlaneEpsilon) any_front = true;
  }
  if (!any_back) return w;
  if (!any_front) {
    // Entirely behind, unless some points touch the plane: keep those (a contact still lets sight through
    // an edge, and keeping it is the conservative choice).
    Winding on;
    for (std::size_t i = 0; i < w.size(); ++i)
      if (d[i] >= -kPlaneEpsilon) on.push_back(w[i]);
    return on;
  }
  Winding out;
  out.reserve(w.size() + 1);  // a convex winding gains at most one corner
  for (std::size_t i = 0; i < w.size(); ++i) {
    const std::size_t j = (i + 1) % w.size();
    if (d[i] >= -kPlaneEpsilon) out.push_back(w[i]);
    // An edge crossing from strictly one side to strictly the other gets the crossing point.
    if ((d[i] > kPlaneEpsilon && d[j] < -kPlaneEpsilon) || (d[i] < -kPlaneEpsilon && d[j] > kPlaneEpsilon)) {
      const double t = d[i] / (d[i] - d[j]);
      out.push_back(w[i] + (w[j] - w[i]) * t);
    }
  }
  return out;
}

Winding clip_front_all(Winding w, const std::vector<Plane>& planes) {
  for (const auto& p : planes) {
    if (w.empty()) break;
    // Most planes leave the winding whole: tested first, since clip_front returns a copy.
    if (!wholly_in_front(w, p)) w = clip_front(w, p);
  }
  return w;
}

Winding convex_hull(const std::vector<model::Vec3>& points, const model::Vec3& normal) {
  if (points.empty()) return {};
  const model::Vec3 n = glm::length(normal) > 0.0 ? glm::normalize(normal) : model::Vec3{0, 0, 1};
  const model::Vec3 helper = std::abs(n.x) < 0.9 ? model::Vec3{1, 0, 0} : model::Vec3{0, 1, 0};
  const model::Vec3 u = glm::normalize(glm::cross(helper, n));
  const model::Vec3 v = glm::cross(n, u);
  std::vector<std::pair<std::pair<double, double>, std::size_t>> q;
  for (std::size_t i = 0; i < points.size(); ++i)
    q.push_back({{glm::dot(points[i] - points[0], u), glm::dot(points[i] - points[0], v)}, i});
  std::sort(q.begin(), q.end());
  q.erase(std::unique(q.begin(), q.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
          q.end());
  if (q.size() == 1) return {points[q[0].second]};
  auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
    const auto& O = q[o].first;
    const auto& A = q[a].first;
    const auto& B = q[b].first;
    return (A.first - O.first) * (B.second - O.second) - (A.second - O.second) * (B.first - O.first);
  };
  // Andrew's monotone chain; collinear points are dropped (cross <= 0 pops).
  std::vector<std::size_t> hull(2 * q.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], i) <= 0.0) --k;
    hull[k++] = i;
  }
  for (std::size_t i = q.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], i) <= 0.0) --k;
    hull[k++] = i;
  }
  if (k > 1) --k;  // the last point repeats the first
  Winding w;
  for (std::size_t i = 0; i < k; ++i) w.push_back(points[q[hull[i]].second]);
  return w;
}

void separating_planes(const Winding& source, const Winding& pass, bool flip, std::vector<Plane>& out) {
  // Normals shorter than this (m^2: cross product of edge and offset) come from a pass point on the line of
  // the source edge: no plane.
  constexpr double kMinNormal = 1e-10;
  const std::size_t ns = source.size(), np = pass.size();
  if (ns < 2 || np == 0) return;
  // Each candidate is judged with its normal c unnormalised, by the signed distances dot(c, x - a), which are
  // its plane's distances times |c|: "beyond kPlaneEpsilon" is then d^2 > kPlaneEpsilon^2 |c|^2 on the side
  // of d's sign. Most candidates fail, and they cost no square root or division; the planes kept are
  // normalised as before. (The portal flow spent 44 % of its time here on the generated M building.)
  constexpr double kEpsilonSquared = kPlaneEpsilon * kPlaneEpsilon;
  for (std::size_t i = 0; i < ns; ++i) {
    const model::Vec3& a = source[i];
    const model::Vec3& b = source[(i + 1) % ns];
    if (ns == 2 && i == 1) break;
    const model::Vec3 edge = b - a;
    for (std::size_t j = 0; j < np; ++j) {
      model::Vec3 c = glm::cross(edge, pass[j] - a);
      const double len2 = glm::dot(c, c);
      if (len2 < kMinNormal * kMinNormal) continue;
      const double tolerance2 = kEpsilonSquared * len2;
      // Source behind: find a source point off the plane to decide the orientation.
      int side = 0;
      for (std::size_t k = 0; k < ns && side == 0; ++k) {
        const double d = glm::dot(c, source[k] - a);
        if (d * d > tolerance2) side = d < 0.0 ? -1 : 1;
      }
      if (side == 0) continue;  // the plane holds the whole source
      if (side > 0) c = -c;
      // Pass wholly in front, or it does not separate.
      bool separates = true, off_plane = false;
      for (std::size_t k = 0; k < np && separates; ++k) {
        const double d = glm::dot(c, pass[k] - a);
        const bool beyond = d * d > tolerance2;
        if (beyond && d < 0.0) separates = false;
        off_plane |= beyond && d > 0.0;
      }
      if (!separates || !off_plane) continue;  // pass behind in part, or wholly in the plane
      const model::Vec3 n = c / std::sqrt(len2);
      const Plane pl{n, -glm::dot(n, a)};
      out.push_back(flip ? pl.flipped() : pl);
    }
  }
}

Winding reached_through(std::span<const model::Vec3> source, const Winding& window, Winding dest) {
  if (source.empty() || window.size() < 3 || dest.size() < 3) return dest;
  const model::Vec3 area = model::area_vector(window);
  if (!(glm::length(area) > 0.0)) return dest;
  const model::Vec3 normal = glm::normalize(area);
  double gap = std::numeric_limits<double>::infinity();
  for (const auto& p : source) gap = std::min(gap, std::abs(glm::dot(normal, p - window.front())));
  if (!(gap > kPlaneEpsilon)) return dest;
  model::Bounds reach;
  for (const auto& p : source) reach.add(p);
  for (const auto& p : dest) reach.add(p);
  const double window_slack = 0.5 * kPlaneEpsilon * gap / std::max(glm::length(reach.size()), gap);
  const Winding source_points(source.begin(), source.end());
  std::vector<Plane> planes;
  separating_planes(source_points, window, false, planes);
  separating_planes(window, source_points, true, planes);
  for (Plane plane : planes) {
    double farthest = -std::numeric_limits<double>::infinity();
    for (const auto& p : source) farthest = std::max(farthest, plane.distance(p));
    plane.d -= farthest;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& w : window) nearest = std::min(nearest, plane.distance(w));
    if (nearest < -window_slack) continue;
    dest = clip_front(dest, plane);
    if (dest.size() < 3) return {};
  }
  return dest;
}

std::vector<VisPolygon> vis_polygons(std::span<const model::VertexRecord> vertices,
                                     std::span<const std::uint32_t> indices,
                                     std::span<const model::PolygonRecord> polygons) {
  std::vector<VisPolygon> out(polygons.size());
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    const auto& rec = polygons[p];
    auto& vp = out[p];
    vp.opaque = rec.role == static_cast<std::uint32_t>(model::Role::Opaque) ||
                rec.role == static_cast<std::uint32_t>(model::Role::Luminaire);
    vp.glass = rec.role == static_cast<std::uint32_t>(model::Role::Glass);
    model::Bounds b;
    model::Vec3 area_normal{0.0};
    std::vector<model::Vec3> pts;
    for (std::uint32_t i = rec.first_index; i + 2 < rec.first_index + rec.index_count; i += 3) {
      std::array<model::Vec3, 3> t;
      for (int k = 0; k < 3; ++k) {
        const auto& v = vertices[indices[i + k]].position;
        t[k] = {v[0], v[1], v[2]};
        b.add(t[k]);
        pts.push_back(t[k]);
      }
      area_normal += glm::cross(t[1] - t[0], t[2] - t[0]);
      vp.triangles.push_back(t);
    }
    vp.drawn_triangles = vp.triangles.size();
    if (b.empty()) continue;
    vp.box = {b.min, b.max};
    const double len = glm::length(area_normal);
    vp.normal = len > 0.0 ? area_normal / len : model::Vec3{0.0};
    vp.hull = convex_hull(pts, vp.normal);
    for (int a = 0; a < 3; ++a)
      if (std::abs(vp.normal[a]) >= kAxialCosine && b.max[a] - b.min[a] <= kInPlaneTolerance) {
        vp.axis = a;
        vp.coord = 0.5 * (b.min[a] + b.max[a]);
      }
  }
  return out;
}

double winding_area(const Winding& w, const model::Vec3& normal) {
  model::Vec3 sum(0.0);
  for (std::size_t i = 0; i < w.size(); ++i) sum += glm::cross(w[i], w[(i + 1) % w.size()]);
  return 0.5 * std::abs(glm::dot(sum, normal));
}

double winding_width(const Winding& w) {
  if (w.size() < 3) return 0.0;
  double width = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < w.size(); ++i) {
    const model::Vec3 a = w[i], edge = w[(i + 1) % w.size()] - a;
    const double len = glm::length(edge);
    if (len == 0.0) continue;  // a repeated point: the next edge measures
    double farthest = 0.0;
    for (const auto& v : w) farthest = std::max(farthest, glm::length(glm::cross(edge, v - a)) / len);
    width = std::min(width, farthest);
  }
  return std::isfinite(width) ? width : 0.0;
}

bool fills_hull(const VisPolygon& p) {
  // The fraction the areas may differ by: rounding, far below any real notch.
  constexpr double kConvexArea = 1e-6;
  if (p.hull.size() < 3) return false;
  double area = 0.0;
  for (const auto& t : p.triangles) area += 0.5 * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
  const double hull = winding_area(p.hull, p.normal);
  return std::abs(hull - area) <= kConvexArea * hull;
}

bool faces_away_from(const VisPolygon& p, const Box& box) {
  if (p.triangles.empty()) return false;
  for (const auto& t : p.triangles) {
    const model::Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    if (n == model::Vec3(0.0)) continue;
    // The box corner farthest along n: on or behind the plane means the whole box is.
    model::Vec3 far;
    for (int a = 0; a < 3; ++a) far[a] = n[a] >= 0.0 ? box.max[a] : box.min[a];
    if (glm::dot(n, far - t[0]) > 0.0) return false;
  }
  return true;
}

}  // namespace walk::compiler
