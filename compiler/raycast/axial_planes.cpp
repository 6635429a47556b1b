#include "compiler/raycast/axial_planes.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace walk::compiler {
namespace {

// Two right triangles whose diagonals' unit normals cancel to within this are complementary halves of
// their common bounding rectangle (normals are unit vectors; 1e-12 is a few thousand ulp).
constexpr double kOppositeEdge = 1e-12;

struct Raw {
  double coord;
  std::uint32_t triangle;
  int edge_count = 0;
  double u0, u1, v0, v1;
  double nu[3], nv[3], c[3];
  std::int16_t sign;
  std::uint32_t polygon;
  bool merged_away = false;
};

}  // namespace

AxialPlanes::AxialPlanes(const LocalTriangles& lt, std::vector<std::uint8_t>& taken,
                         const BlockSizing& sizing) {
  std::vector<Raw> raw[3];
  double area = 0.0;  // of the surfaces taken, for the blocks' mean free path
  for (std::uint32_t i = 0; i < lt.triangles.size(); ++i) {
    const Triangle& t = lt.triangles[i];
    int k = -1;
    for (int a = 0; a < 3 && k < 0; ++a)
      if (t.a[a] == t.b[a] && t.b[a] == t.c[a]) k = a;
    if (k < 0) continue;
    taken[i] = 1;
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    const double pu[3] = {t.a[u], t.b[u], t.c[u]};
    const double pv[3] = {t.a[v], t.b[v], t.c[v]};
    const double area2 = (pu[1] - pu[0]) * (pv[2] - pv[0]) - (pv[1] - pv[0]) * (pu[2] - pu[0]);
    if (area2 == 0.0 || !std::isfinite(area2)) continue;  // degenerate: no ray can hit it
    area += 0.5 * std::abs(area2);
    Raw r{};
    r.coord = t.a[k];
    r.triangle = i;
    r.polygon = t.polygon;
    r.sign = area2 > 0.0 ? 1 : -1;
    r.u0 = std::min({pu[0], pu[1], pu[2]}) - kEdgeSlack;
    r.u1 = std::max({pu[0], pu[1], pu[2]}) + kEdgeSlack;
    r.v0 = std::min({pv[0], pv[1], pv[2]}) - kEdgeSlack;
    r.v1 = std::max({pv[0], pv[1], pv[2]}) + kEdgeSlack;
    for (int e = 0; e < 3; ++e) {
      const int f = (e + 1) % 3;
      if (pu[e] == pu[f] || pv[e] == pv[f]) continue;  // lies on the bounds: the bounds test covers it
      double nu = -(pv[f] - pv[e]) * r.sign, nv = (pu[f] - pu[e]) * r.sign;
      const double len = std::hypot(nu, nv);
      nu /= len;
      nv /= len;
      r.nu[r.edge_count] = nu;
      r.nv[r.edge_count] = nv;
      r.c[r.edge_count] = -(nu * pu[e] + nv * pv[e]) + kEdgeSlack;
      ++r.edge_count;
    }
    raw[k].push_back(r);
  }

  std::vector<PlaneBox> boxes;  // every element's extent, for the blocks
  std::vector<Element> elements;
  for (int k = 0; k < 3; ++k) {
    auto& list = raw[k];
    std::stable_sort(list.begin(), list.end(), [](const Raw& a, const Raw& b) { return a.coord < b.coord; });
    for (std::size_t first = 0; first < list.size();) {
      std::size_t last = first;
      while (last < list.size() && list[last].coord == list[first].coord) ++last;
      // Two right triangles of one polygon on either side of their bounding rectangle's diagonal: one
      // rectangle, tested by its bounds alone.
      std::vector<std::size_t> halves;
      for (std::size_t i = first; i < last; ++i)
        if (list[i].edge_count == 1) halves.push_back(i);
      const auto key = [&](std::size_t i) {
        const Raw& r = list[i];
        return std::tie(r.polygon, r.sign, r.u0, r.u1, r.v0, r.v1);
      };
      std::sort(halves.begin(), halves.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
      for (std::size_t h = 0; h + 1 < halves.size(); ++h) {
        Raw& a = list[halves[h]];
        Raw& b = list[halves[h + 1]];
        if (key(halves[h]) != key(halves[h + 1])) continue;
        if (std::abs(a.nu[0] + b.nu[0]) > kOppositeEdge || std::abs(a.nv[0] + b.nv[0]) > kOppositeEdge)
          continue;
        a.edge_count = 0;
        a.triangle = std::min(a.triangle, b.triangle);
        b.merged_away = true;
        ++stats_.rectangles;
        ++h;
      }

      for (std::size_t i = first; i < last; ++i) {
        const Raw& r = list[i];
        ++stats_.triangles;
        if (r.merged_away) continue;
        boxes.push_back({k, static_cast<std::uint32_t>(stats_.planes[k]),
                         static_cast<std::uint32_t>(elements.size()), r.coord, r.u0, r.u1, r.v0, r.v1});
        elements.push_back({r.u0, r.u1, r.v0, r.v1, static_cast<std::uint32_t>(edges_.size()),
                            static_cast<std::uint16_t>(r.edge_count), r.sign, r.triangle, r.polygon});
        for (int j = 0; j < r.edge_count; ++j) edges_.push_back({r.nu[j], r.nv[j], r.c[j]});
      }
      ++stats_.planes[k];
      first = last;
    }
  }
  stats_.elements = elements.size();
  const auto target = std::max<std::size_t>(
      1, static_cast<std::size_t>(sizing.per_element * static_cast<double>(elements.size())));
  blocks_ = PlaneBlocks(boxes, target, sizing.planes_per_layer, sizing.lanes, area);
  if (sizing.planes_per_layer > 0.0 && blocks_.stats().longest > kLongestListing)
    blocks_ = PlaneBlocks(boxes, target, 0.0, sizing.lanes, area);
  // Each block's elements copied in place: a crossing reads one contiguous run, with no index to chase (the
  // walk is bound by memory latency on big buildings).
  cell_elements_.reserve(blocks_.items().size());
  for (const std::uint32_t i : blocks_.items()) cell_elements_.push_back(elements[i]);
  stats_.cell_entries = cell_elements_.size();
}

template <bool kAny>
bool AxialPlanes::walk(const model::Vec3& o, const model::Vec3& d, double tmin, double tmax, double tie,
                       RayHit* best, MarkedSpan* marked) const {
  double limit = tmax;
  bool any = false;
  const double dk[3] = {d.x, d.y, d.z};  // not glm's operator[], a switch on the axis
  blocks_.walk<!kAny>(
      o, d, tmin, limit,
      [&](int k, std::uint32_t first, std::uint32_t count, double t, double pu, double pv) {
        for (std::uint32_t c = first; c < first + count; ++c) {
          const Element& e = cell_elements_[c];
          if (e.u0 > pu) break;  // the listing is in increasing u0: no later element reaches the point
          // So pu >= u0 here (a NaN pu fails the other tests). One branch, not three: whether a point passes
          // an element's bounds is unpredictable.
          if (!((pu <= e.u1) & (pv >= e.v0) & (pv <= e.v1))) continue;
          bool inside = true;
          for (std::uint32_t j = e.edge_first; j < e.edge_first + e.edge_count; ++j) {
            const EdgeLine& l = edges_[j];
            if (l.nu * pu + l.nv * pv + l.c < 0.0) {
              inside = false;
              break;
            }
          }
          if (!inside) continue;
          if constexpr (kAny) {
            any = true;
            return true;
          } else {
            const bool front = e.normal_sign * dk[k] < 0.0;
            if (better_hit(t, front, e.triangle, *best, tie)) {
              *best = {t, e.triangle, e.polygon, front};
              limit = std::min(tmax, t + tie);
            }
          }
        }
        return false;
      },
      [&](std::uint32_t first, std::uint32_t end) {
        const char* p = reinterpret_cast<const char*>(cell_elements_.data() + first);
        const char* q = reinterpret_cast<const char*>(cell_elements_.data() + end);
        for (int line = 0; line < 4 && p < q; ++line, p += 64) __builtin_prefetch(p);
      },
      marked);
  return any;
}

void AxialPlanes::closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                          double tie, RayHit& best, MarkedSpan* marked) const {
  if (best.hit()) tmax = std::min(tmax, best.t + tie);
  walk<false>(origin, dir, tmin, tmax, tie, &best, marked);
}

bool AxialPlanes::occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                           MarkedSpan* marked) const {
  return walk<true>(origin, dir, tmin, tmax, 0.0, nullptr, marked);
}

std::size_t AxialPlanes::memory_bytes() const {
  return cell_elements_.capacity() * sizeof(Element) + edges_.capacity() * sizeof(EdgeLine) +
         blocks_.memory_bytes();
}

}  // namespace walk::compiler
