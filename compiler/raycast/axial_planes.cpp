#include "compiler/raycast/axial_planes.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace walk::compiler {
namespace {

// Grid cells per element in a plane: about two keeps the lists per cell short without many empty cells.
constexpr double kCellsPerElement = 2.0;
// Planes with this many elements or fewer keep one cell: testing them all is cheaper than a lookup.
constexpr std::size_t kDirectList = 4;
constexpr std::uint32_t kMaxGridSide = 1024;
// Two right triangles whose diagonals' unit normals cancel to within this are complementary halves of
// their common bounding rectangle (normals are unit vectors; 1e-12 is a few thousand ulp).
constexpr double kOppositeEdge = 1e-12;

// A plane joins the structure only when it holds at least this many polygons or this fraction of the model's
// cross-section in polygon area: every ray crossing a plane's coordinate pays a step, so the many small
// axial faces of a sculpted mesh (mouldings, furniture) are cheaper in the BSP. A building's walls and
// floors pass easily (the house's smallest kept plane holds a door).
constexpr std::size_t kPlaneMinElements = 32;
constexpr double kPlaneMinAreaFraction = 0.01;

struct Raw {
  double coord;
  double area;
  std::uint32_t triangle;
  int edge_count = 0;
  double u0, u1, v0, v1;
  double nu[3], nv[3], c[3];
  std::int16_t sign;
  std::uint32_t polygon;
  bool merged_away = false;
};

std::uint32_t cell_of(double x, double x0, double inv, std::uint32_t n) {
  const double f = (x - x0) * inv;
  if (!(f > 0.0)) return 0;  // also NaN
  return std::min(n - 1, static_cast<std::uint32_t>(std::min(f, 4.0e9)));
}

// The plane's own (u, v) axes for each axis k: (k + 1) % 3 and (k + 2) % 3.
constexpr int kU[3] = {1, 2, 0};
constexpr int kV[3] = {2, 0, 1};

// First index whose coordinate is >= x (kUpper: > x), without branches: the walk does three of these per ray.
template <bool kUpper>
std::ptrdiff_t bound(const std::vector<double>& coords, double x) {
  const double* base = coords.data();
  std::size_t n = coords.size();
  while (n > 1) {
    const std::size_t half = n / 2;
    base = (kUpper ? !(x < base[half]) : base[half] < x) ? base + half : base;
    n -= half;
  }
  return (base - coords.data()) + ((kUpper ? !(x < *base) : *base < x) ? 1 : 0);
}

}  // namespace

AxialPlanes::AxialPlanes(const LocalTriangles& lt, std::vector<std::uint8_t>& taken) {
  std::vector<Raw> raw[3];
  model::Bounds bounds;
  for (const auto& t : lt.triangles) {
    bounds.add(t.a);
    bounds.add(t.b);
    bounds.add(t.c);
  }
  const model::Vec3 extent = bounds.empty() ? model::Vec3(0.0) : bounds.size();
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
    Raw r{};
    r.coord = t.a[k];
    r.area = 0.5 * std::abs(area2);
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

  for (int k = 0; k < 3; ++k) {
    auto& list = raw[k];
    std::stable_sort(list.begin(), list.end(), [](const Raw& a, const Raw& b) { return a.coord < b.coord; });
    for (std::size_t first = 0; first < list.size();) {
      std::size_t last = first;
      while (last < list.size() && list[last].coord == list[first].coord) ++last;
      double area = 0.0;
      for (std::size_t i = first; i < last; ++i) area += list[i].area;
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      if (last - first < kPlaneMinElements && area < kPlaneMinAreaFraction * extent[u] * extent[v]) {
        for (std::size_t i = first; i < last; ++i) taken[list[i].triangle] = 0;  // left to the BSP
        ++stats_.planes_left;
        first = last;
        continue;
      }

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

      struct {
        double u0, u1, v0, v1, inv_du, inv_dv;
        std::uint32_t nu, nv, cell_first;
      } p{};
      p.u0 = p.v0 = INFINITY;
      p.u1 = p.v1 = -INFINITY;
      std::vector<Element> elements;
      for (std::size_t i = first; i < last; ++i) {
        const Raw& r = list[i];
        ++stats_.triangles;
        if (r.merged_away) continue;
        Element e{r.u0,
                  r.u1,
                  r.v0,
                  r.v1,
                  static_cast<std::uint32_t>(edges_.size()),
                  static_cast<std::uint16_t>(r.edge_count),
                  r.sign,
                  r.triangle,
                  r.polygon};
        for (int j = 0; j < r.edge_count; ++j) edges_.push_back({r.nu[j], r.nv[j], r.c[j]});
        elements.push_back(e);
        p.u0 = std::min(p.u0, r.u0);
        p.u1 = std::max(p.u1, r.u1);
        p.v0 = std::min(p.v0, r.v0);
        p.v1 = std::max(p.v1, r.v1);
      }
      const std::size_t m = elements.size();
      stats_.elements += m;
      p.nu = p.nv = 1;
      if (m > kDirectList) {
        const double w = p.u1 - p.u0, h = p.v1 - p.v0, target = kCellsPerElement * static_cast<double>(m);
        p.nu = static_cast<std::uint32_t>(
            std::clamp(std::lround(std::sqrt(target * w / h)), 1L, static_cast<long>(kMaxGridSide)));
        p.nv = static_cast<std::uint32_t>(
            std::clamp(std::lround(target / p.nu), 1L, static_cast<long>(kMaxGridSide)));
      }
      p.inv_du = p.nu / (p.u1 - p.u0);
      p.inv_dv = p.nv / (p.v1 - p.v0);
      p.cell_first = static_cast<std::uint32_t>(cell_start_.size());
      // Counting sort of the elements into the cells their bounds overlap (same rounding as the lookup).
      const std::size_t cells = std::size_t{p.nu} * p.nv;
      std::vector<std::uint32_t> count(cells + 1, 0);
      auto each_cell = [&](const Element& e, auto&& fn) {
        const std::uint32_t iu0 = cell_of(e.u0, p.u0, p.inv_du, p.nu),
                            iu1 = cell_of(e.u1, p.u0, p.inv_du, p.nu);
        const std::uint32_t iv0 = cell_of(e.v0, p.v0, p.inv_dv, p.nv),
                            iv1 = cell_of(e.v1, p.v0, p.inv_dv, p.nv);
        for (std::uint32_t iv = iv0; iv <= iv1; ++iv)
          for (std::uint32_t iu = iu0; iu <= iu1; ++iu) fn(std::size_t{iv} * p.nu + iu);
      };
      for (const auto& e : elements) each_cell(e, [&](std::size_t c) { ++count[c + 1]; });
      for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
      const auto base = static_cast<std::uint32_t>(cell_elements_.size());
      for (std::size_t c = 0; c <= cells; ++c) cell_start_.push_back(base + count[c]);
      cell_elements_.resize(base + count[cells]);
      for (const auto& e : elements)
        each_cell(e, [&](std::size_t c) { cell_elements_[base + count[c]++] = e; });
      stats_.cells += cells;

      coords_[k].push_back(list[first].coord);
      bounds_[k].push_back({list[first].coord, p.u0, p.u1, p.v0, p.v1});
      grids_[k].push_back({p.inv_du, p.inv_dv, p.nu, p.nv, p.cell_first});
      first = last;
    }
    stats_.planes[k] = bounds_[k].size();
  }
  stats_.cell_entries = cell_elements_.size();
}

template <bool kAny>
bool AxialPlanes::walk(const model::Vec3& o, const model::Vec3& d, double tmin, double tmax, double tie,
                       RayHit* best) const {
  // Per axis: the next plane ahead of the ray, its index step, and its ray parameter.
  double next_t[3];
  std::ptrdiff_t index[3], end[3], step[3];
  double inv[3];
  for (int k = 0; k < 3; ++k) {
    next_t[k] = INFINITY;
    index[k] = end[k] = 0;
    step[k] = 0;
    const auto& coords = coords_[k];
    if (!(d[k] != 0.0) || coords.empty()) continue;  // parallel to this axis' planes (or NaN)
    inv[k] = 1.0 / d[k];
    const double start = o[k] + std::max(tmin, 0.0) * d[k];
    if (d[k] > 0.0) {
      index[k] = bound<false>(coords, start);
      end[k] = static_cast<std::ptrdiff_t>(coords.size());
      step[k] = 1;
    } else {
      index[k] = bound<true>(coords, start) - 1;
      end[k] = -1;
      step[k] = -1;
    }
    if (index[k] != end[k]) next_t[k] = (coords[index[k]] - o[k]) * inv[k];
  }
  double limit = tmax;
  for (;;) {
    const int k =
        next_t[0] <= next_t[1] ? (next_t[0] <= next_t[2] ? 0 : 2) : (next_t[1] <= next_t[2] ? 1 : 2);
    const double t = next_t[k];
    if (!(t < limit)) break;
    const std::ptrdiff_t pi = index[k];
    index[k] += step[k];
    next_t[k] = index[k] != end[k] ? (bounds_[k][index[k]].coord - o[k]) * inv[k] : INFINITY;
    if (!(t > tmin)) continue;

    const PlaneBounds& b = bounds_[k][pi];
    const int u = kU[k], v = kV[k];
    const double pu = o[u] + t * d[u];
    const double pv = o[v] + t * d[v];
    if (pu < b.u0 || pu > b.u1 || pv < b.v0 || pv > b.v1) continue;
    const PlaneGrid& p = grids_[k][pi];
    const std::uint32_t cell =
        p.cell_first + cell_of(pv, b.v0, p.inv_dv, p.nv) * p.nu + cell_of(pu, b.u0, p.inv_du, p.nu);
    for (std::uint32_t c = cell_start_[cell]; c < cell_start_[cell + 1]; ++c) {
      const Element& e = cell_elements_[c];
      if (pu < e.u0 || pu > e.u1 || pv < e.v0 || pv > e.v1) continue;
      bool inside = true;
      for (std::uint32_t j = e.edge_first; j < e.edge_first + e.edge_count; ++j) {
        const EdgeLine& l = edges_[j];
        if (l.nu * pu + l.nv * pv + l.c < 0.0) {
          inside = false;
          break;
        }
      }
      if (!inside) continue;
      if constexpr (kAny) return true;
      const bool front = e.normal_sign * d[k] < 0.0;
      if (better_hit(t, front, e.triangle, *best, tie)) {
        *best = {t, e.triangle, e.polygon, front};
        limit = std::min(tmax, t + tie);
      }
    }
  }
  return false;
}

void AxialPlanes::closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                          double tie, RayHit& best) const {
  if (best.hit()) tmax = std::min(tmax, best.t + tie);
  walk<false>(origin, dir, tmin, tmax, tie, &best);
}

bool AxialPlanes::occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin,
                           double tmax) const {
  return walk<true>(origin, dir, tmin, tmax, 0.0, nullptr);
}

std::size_t AxialPlanes::memory_bytes() const {
  std::size_t bytes = cell_elements_.capacity() * sizeof(Element) + edges_.capacity() * sizeof(EdgeLine) +
                      cell_start_.capacity() * sizeof(std::uint32_t);
  for (int k = 0; k < 3; ++k)
    bytes += coords_[k].capacity() * sizeof(double) + bounds_[k].capacity() * sizeof(PlaneBounds) +
             grids_[k].capacity() * sizeof(PlaneGrid);
  return bytes;
}

}  // namespace walk::compiler
