#include "compiler/raycast/polygon_bsp.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

constexpr std::size_t kLeafSize = 4;
constexpr int kMaxDepth = 56;
// Splitting planes tried per node: planes of this many polygons spread through the node's list, plus the
// nine axis planes.
constexpr std::size_t kCandidates = 8;
// Candidates are scored on at most this many of the node's polygons.
constexpr std::size_t kScoreSample = 256;
// Cost of visiting a node, in triangle tests (surface-area heuristic).
constexpr double kTraversalCost = 1.0;
// Nodes with more polygons than this are split even when the cost estimate does not ask for it.
constexpr std::size_t kMaxLeaf = 16;
// A vertex closer than this to a plane lies in it (1 nm, as kEdgeSlack); it also widens the ray intervals
// on either side of a split so that rounding near the plane never skips the side holding the hit.
constexpr double kPlaneEps = 1e-9;

enum Side { kOn, kFront, kBack, kStraddle };

// A triangle in the plane goes to the side its front faces: the tree keeps polygons in its leaves only, so
// a wall of many coplanar polygons is split further in space instead of being one long list at a node.
Side classify(const Triangle& t, const model::Vec3& tn, const model::Vec3& n, double offset) {
  const double d[3] = {glm::dot(n, t.a) - offset, glm::dot(n, t.b) - offset, glm::dot(n, t.c) - offset};
  const double lo = std::min({d[0], d[1], d[2]}), hi = std::max({d[0], d[1], d[2]});
  if (hi <= kPlaneEps && lo >= -kPlaneEps) return glm::dot(tn, n) >= 0.0 ? kFront : kBack;
  if (lo >= -kPlaneEps) return kFront;
  if (hi <= kPlaneEps) return kBack;
  return kStraddle;
}

double half_area(const model::Vec3& lo, const model::Vec3& hi) {
  const model::Vec3 d = glm::max(hi - lo, model::Vec3(0.0));
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// `inv` is 1/dir per axis, computed once per ray. A NaN (the origin on the slab face of a parallel ray)
// leaves t0 and t1 as they are: std::max(t0, NaN) and std::min(t1, NaN) return their first argument. No
// branch per axis: the three slabs are folded and compared once.
inline bool slab(const model::Vec3& lo, const model::Vec3& hi, const model::Vec3& o, const model::Vec3& inv,
                 double& t0, double& t1) {
  for (int a = 0; a < 3; ++a) {
    const double n = (lo[a] - o[a]) * inv[a], f = (hi[a] - o[a]) * inv[a];
    t0 = std::max(t0, std::min(n, f));
    t1 = std::min(t1, std::max(n, f));
  }
  return t0 <= t1;
}

}  // namespace

PolygonBsp::PolygonBsp(const LocalTriangles& triangles, std::vector<std::uint32_t> ids) : tris_(&triangles) {
  stats_.triangles = ids.size();
  if (!ids.empty()) build(ids, 0);
  stats_.nodes = nodes_.size();
  stats_.references = items_.size();
}

std::uint32_t PolygonBsp::build(std::vector<std::uint32_t>& ids, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_[index].depth = depth;
  stats_.depth = std::max(stats_.depth, depth);
  const auto& tris = tris_->triangles;
  model::Vec3 lo(INFINITY), hi(-INFINITY);
  for (const auto i : ids) {
    lo = glm::min(lo, glm::min(tris[i].a, glm::min(tris[i].b, tris[i].c)));
    hi = glm::max(hi, glm::max(tris[i].a, glm::max(tris[i].b, tris[i].c)));
  }
  nodes_[index].lo = lo - kPlaneEps;
  nodes_[index].hi = hi + kPlaneEps;
  auto keep_here = [&](const std::vector<std::uint32_t>& here) {
    nodes_[index].first = static_cast<std::uint32_t>(items_.size());
    nodes_[index].count = static_cast<std::uint32_t>(here.size());
    items_.insert(items_.end(), here.begin(), here.end());
  };
  if (ids.size() <= kLeafSize || depth >= kMaxDepth) {
    keep_here(ids);
    return index;
  }

  // Candidate planes: some polygons' own planes and axis planes at a quarter, half and three quarters.
  std::vector<std::pair<model::Vec3, double>> candidates;
  for (std::size_t j = 0; j < kCandidates && j < ids.size(); ++j) {
    const auto i = ids[j * ids.size() / std::min(kCandidates, ids.size())];
    const double len = glm::length(tris_->normals[i]);
    if (!(len > 0.0)) continue;
    const model::Vec3 n = tris_->normals[i] / len;
    candidates.emplace_back(n, glm::dot(n, tris[i].a));
  }
  for (int a = 0; a < 3; ++a) {
    model::Vec3 n(0.0);
    n[a] = 1.0;
    for (const double f : {0.25, 0.5, 0.75}) candidates.emplace_back(n, lo[a] + f * (hi[a] - lo[a]));
  }
  // Surface-area cost: the chance that a ray through this node visits a child is the ratio of their
  // surface areas; it tests the child's polygons then. Straddlers count on both sides.
  const std::size_t stride = std::max<std::size_t>(1, ids.size() / kScoreSample);
  const double node_area = half_area(lo, hi);
  double best_cost = INFINITY;
  std::size_t sampled = 0;
  int best = -1;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    model::Vec3 flo(INFINITY), fhi(-INFINITY), blo(INFINITY), bhi(-INFINITY);
    std::size_t nf = 0, nb = 0;
    sampled = 0;
    for (std::size_t j = 0; j < ids.size(); j += stride, ++sampled) {
      const Triangle& t = tris[ids[j]];
      const Side side = classify(t, tris_->normals[ids[j]], candidates[c].first, candidates[c].second);
      const model::Vec3 tlo = glm::min(t.a, glm::min(t.b, t.c)), thi = glm::max(t.a, glm::max(t.b, t.c));
      if (side != kBack) {
        ++nf;
        flo = glm::min(flo, tlo);
        fhi = glm::max(fhi, thi);
      }
      if (side == kBack || side == kStraddle) {
        ++nb;
        blo = glm::min(blo, tlo);
        bhi = glm::max(bhi, thi);
      }
    }
    if (nf == sampled || nb == sampled) continue;  // everything on one side: no progress
    const double cost = kTraversalCost + (half_area(flo, fhi) * static_cast<double>(nf) +
                                          half_area(blo, bhi) * static_cast<double>(nb)) /
                                             std::max(node_area, 1e-300);
    if (cost < best_cost) {
      best_cost = cost;
      best = static_cast<int>(c);
    }
  }
  // A leaf when no split is expected to test fewer polygons than the leaf would (up to kMaxLeaf).
  if (best < 0 || (best_cost >= static_cast<double>(sampled) && ids.size() <= kMaxLeaf)) {
    keep_here(ids);
    return index;
  }
  const auto [n, offset] = candidates[best];
  std::vector<std::uint32_t> front, back;
  for (const auto i : ids) {
    switch (classify(tris[i], tris_->normals[i], n, offset)) {
      case kOn:
        break;  // classify never answers kOn
      case kFront:
        front.push_back(i);
        break;
      case kBack:
        back.push_back(i);
        break;
      case kStraddle:
        front.push_back(i);
        back.push_back(i);
        break;
    }
  }
  if (front.size() == ids.size() || back.size() == ids.size()) {  // no progress after all
    keep_here(ids);
    return index;
  }
  nodes_[index].normal = n;
  nodes_[index].offset = offset;
  for (int a = 0; a < 3; ++a)
    if (n[a] == 1.0 && n[(a + 1) % 3] == 0.0 && n[(a + 2) % 3] == 0.0) nodes_[index].axis = a;
  if (nodes_[index].axis >= 0) ++stats_.axis_splits;
  std::vector<std::uint32_t>().swap(ids);
  // Neither side is empty here (an empty one would have left the other with every polygon): an inner node
  // always has both children, which the search relies on.
  if (!front.empty()) {
    const std::uint32_t f = build(front, depth + 1);
    nodes_[index].front = f;
    nodes_[f].parent = index;
  }
  if (!back.empty()) {
    const std::uint32_t b = build(back, depth + 1);
    nodes_[index].back = b;
    nodes_[b].parent = index;
  }
  return index;
}

std::uint32_t PolygonBsp::enclosing(const model::Vec3& lo, const model::Vec3& hi) const {
  if (nodes_.empty()) return kNoHit;
  const model::Vec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  std::uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    if (n.count > 0) return node;  // a leaf
    // The box's extent along the normal: its centre's distance, plus or minus its half extents projected.
    const double dist = glm::dot(n.normal, centre) - n.offset;
    const double reach = glm::dot(glm::abs(n.normal), half) + 1e-15 * std::abs(dist);
    // Beyond twice the tolerance: no triangle of the other side (all within kPlaneEps of it) reaches the box.
    if (dist - reach > 2.0 * kPlaneEps)
      node = n.front;
    else if (dist + reach < -2.0 * kPlaneEps)
      node = n.back;
    else
      return node;
  }
}

std::uint32_t PolygonBsp::common_ancestor(std::span<const std::uint32_t> nodes) const {
  std::uint32_t common = kNoHit;
  for (std::uint32_t n : nodes) {
    if (n == kNoHit) continue;
    if (common == kNoHit) {
      common = n;
      continue;
    }
    while (nodes_[n].depth > nodes_[common].depth) n = nodes_[n].parent;
    while (nodes_[common].depth > nodes_[n].depth) common = nodes_[common].parent;
    while (n != common) {
      n = nodes_[n].parent;
      common = nodes_[common].parent;
    }
  }
  return common;
}

template <bool kAny>
bool PolygonBsp::search(std::uint32_t start, const model::Vec3& o, const model::Vec3& dir, double tmin,
                        double tmax, double tie, RayHit* best) const {
  struct Entry {
    std::uint32_t node;
    double t0, t1;  // the ray's interval in the node's box, already slab-tested
  };
  Entry stack[2 * kMaxDepth + 8];
  int top = 0;
  double limit = tmax;
  if (!kAny && best->hit()) limit = std::min(limit, best->t + tie);
  const model::Vec3 inv(1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z);
  // Plain arrays for the axis splits: glm's operator[] with a run-time axis is a switch.
  const double oa[3] = {o.x, o.y, o.z}, da[3] = {dir.x, dir.y, dir.z}, inva[3] = {inv.x, inv.y, inv.z};
  double t0 = tmin, t1 = limit;
  if (!slab(nodes_[start].lo, nodes_[start].hi, o, inv, t0, t1)) return false;
  // The shear is set up at the first leaf the ray reaches: most rays that meet the tree's bounds (the whole
  // building's, for walls spread through it) leave by empty space or an axial hit before any leaf.
  ShearedRay ray;
  const auto& tris = tris_->triangles;
  std::uint32_t node = start;
  for (;;) {
    const Node& n = nodes_[node];
    if (n.count > 0) {
      if (!ray.valid) {
        ray = ShearedRay(o, dir);
        if (!ray.valid) return false;
      }
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j) {
        const std::uint32_t i = items_[j];
        double t = 0.0;
        if (!intersect_watertight(ray, tris[i].a, tris[i].b, tris[i].c, tmin, limit, t)) continue;
        if constexpr (kAny) return true;
        const bool front = tris_->front(i, dir);
        if (better_hit(t, front, i, *best, tie)) {
          *best = {t, i, tris[i].polygon, front};
          limit = std::min(tmax, t + tie);
        }
      }
    } else {
      // An inner node (the build leaves no side empty, so it has both children): the children whose boxes
      // the ray meets within its interval on their side of the split, near side first. Both are tested and
      // the next node picked by selects: one unpredictable branch a node instead of six.
      t1 = std::min(t1, limit);
      // Distance to the split plane and approach speed; an axis plane needs neither dot products nor a
      // division.
      double dist, denom, inv_denom;
      if (n.axis >= 0) {
        dist = oa[n.axis] - n.offset;
        denom = da[n.axis];
        inv_denom = inva[n.axis];
      } else {
        dist = glm::dot(n.normal, o) - n.offset;
        denom = glm::dot(n.normal, dir);
        inv_denom = 1.0 / denom;
      }
      // Rounding margin in t: the classification tolerance plus the rounding of dist, over the approach
      // speed.
      const double margin = (2.0 * kPlaneEps + 1e-15 * std::abs(dist)) * std::abs(inv_denom);
      std::uint32_t near_child, far_child;
      double a0 = t0, b0 = t1, a1 = t0, b1 = t1;
      if (!(std::abs(denom) > 0.0) || !std::isfinite(margin)) {  // parallel to the plane: stays on its side
        near_child = n.front;
        far_child = n.back;
        if (!(dist >= -kPlaneEps)) b0 = -INFINITY;
        if (!(dist <= kPlaneEps)) b1 = -INFINITY;
      } else {
        const double ts = -dist * inv_denom;
        const bool up = denom > 0.0;  // the ray is on the back side before ts
        near_child = up ? n.back : n.front;
        far_child = up ? n.front : n.back;
        b0 = std::min(t1, ts + margin);
        a1 = std::max(t0, ts - margin);
      }
      // A side whose interval is already empty (the ray leaves the node before the plane) is not loaded:
      // in a big tree (the conference room's) its box is a cache miss.
      const bool near_hit = a0 <= b0 && slab(nodes_[near_child].lo, nodes_[near_child].hi, o, inv, a0, b0);
      const bool far_hit = a1 <= b1 && slab(nodes_[far_child].lo, nodes_[far_child].hi, o, inv, a1, b1);
      stack[top] = {far_child, a1, b1};
      top += near_hit & far_hit;
      if (near_hit | far_hit) {
        node = near_hit ? near_child : far_child;
        t0 = near_hit ? a0 : a1;
        t1 = near_hit ? b0 : b1;
        continue;
      }
    }
    for (;;) {  // the nearest pending node still in front of the best hit
      if (top == 0) return false;
      const Entry& e = stack[--top];
      if (e.t0 <= limit) {
        node = e.node;
        t0 = e.t0;
        t1 = e.t1;
        break;
      }
    }
  }
}

void PolygonBsp::closest(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                         double tie, RayHit& best, std::uint32_t start) const {
  if (!nodes_.empty()) search<false>(start, origin, dir, tmin, tmax, tie, &best);
}

bool PolygonBsp::occluded(const model::Vec3& origin, const model::Vec3& dir, double tmin, double tmax,
                          std::uint32_t start) const {
  return !nodes_.empty() && search<true>(start, origin, dir, tmin, tmax, 0.0, nullptr);
}

std::size_t PolygonBsp::memory_bytes() const {
  return nodes_.capacity() * sizeof(Node) + items_.capacity() * sizeof(std::uint32_t);
}

}  // namespace walk::compiler
