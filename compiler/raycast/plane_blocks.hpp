#pragma once
// Empty-space skipping for the axial plane walk. The paper's walk steps through every plane whose coordinate
// the ray passes, including the many planes of rooms far off to the side: in an open Quake level a ray
// crosses a hundred planes to reach a wall, and the walk, not the polygon tests, was 43% of the time. Here
// model space is cut into a uniform grid of blocks; each block lists, per axis and sorted by coordinate, only
// the planes with a polygon inside it, with the bounds of those polygons. A ray steps from block to block (3D
// DDA) and, inside each block, walks the block's three short sorted lists in merged order of ray parameter,
// exactly as the paper's walk does over the whole model. Empty blocks cost one step.
//
// Consistency: every t is computed as (coordinate - origin) / dir, for plane coordinates and block edges
// alike, so a plane between two edges is crossed between the ray's entry into and exit from that layer of
// blocks. Polygons are listed in every block their bounds reach within kBlockMargin, which covers the
// rounding of the in-plane hit point (a few ulp of the local coordinates).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "compiler/raycast/crossing_lanes.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// The plane's own (u, v) axes for each axis k: (k + 1) % 3 and (k + 2) % 3.
inline constexpr int kPlaneU[3] = {1, 2, 0};
inline constexpr int kPlaneV[3] = {2, 0, 1};

// Relative to the grid's diagonal: 1e-9 of a 1 km building is 1 um, a million times the rounding of a hit
// point computed from an origin inside the model (origins up to ~1e6 diagonals away stay covered).
inline constexpr double kBlockMargin = 1e-9;
// Blocks with at most this many listings are tested all at once by the AVX-512 lanes (PlaneBlocks::walk).
inline constexpr std::uint32_t kGathered = 16;
// Blocks with up to this many listings are tested by the lanes too where rays usually cross a block rather
// than end in it (PlaneBlocks::most_gathered_); bigger ones always take the merge.
inline constexpr std::uint32_t kGatheredMax = 64;

// How finely the blocks cut space.
struct BlockSizing {
  // Blocks per element. More skip empty space more finely but copy big polygons into many listings and make
  // a ray step through more blocks; fewer make longer listings, which are contiguous and cheap to scan.
  // Memory latency dominates, so fewer won: in the block-size sweep (docs/RAYCAST.md "Design decisions";
  // `walk bench rays --casters axial@0.02,axial@0.05,...`) 0.05 was fastest or within noise of it on the
  // house, office, E1M1 and DM1; the tower kept gaining down to 0.02.
  double per_element = 0.05;
  // A layer of blocks along an axis pays only when a ray would otherwise cross several of that axis' planes
  // in it: at most one layer per this many planes (0: no limit). Small buildings (the office: 7 planes an
  // axis) then get one block, where the walk over the whole model is cheaper than stepping through blocks
  // (the office's occlusion rays ran at 0.55 of Embree with 8 blocks, 0.83 with 1). If that leaves a listing
  // longer than kLongestListing (a big tiled floor in a small model), the limit is dropped.
  double planes_per_layer = 4.0;
  // Test a block's listings eight at a time with AVX-512 where the CPU has it (crossing_lanes.hpp); false
  // keeps the scalar merge (the tests run both).
  bool lanes = true;
};
inline constexpr std::size_t kLongestListing = 64;

// One element's extent in its plane: the element lies in plane `plane` (index among the axis' planes) at
// `coord` along `axis`, within [u0, u1] x [v0, v1] of the plane's (u, v) axes.
struct PlaneBox {
  int axis;
  std::uint32_t plane;
  std::uint32_t item;  // the element's index in the owner's list
  double coord;
  double u0, u1, v0, v1;
};

// The span of ray parameter over which a walk passed marked blocks (PlaneBlocks::mark), or their marked
// boxes, widened by the blocks' margin: empty when it passed none.
// `tags` are the distinct tags (PlaneBlocks::tag_marks) of the marked blocks passed, up to kSpanTags of
// them; `tag_count` is kSpanTags + 1 when there were more.
inline constexpr int kSpanTags = 4;
struct MarkedSpan {
  double first = INFINITY, last = -INFINITY;
  std::uint32_t tags[kSpanTags] = {};
  int tag_count = 0;
  [[nodiscard]] bool empty() const { return !(first <= last); }
  [[nodiscard]] bool all_tags() const { return tag_count <= kSpanTags; }
  void add_tag(std::uint32_t tag) {
    for (int i = 0; i < std::min(tag_count, kSpanTags); ++i)
      if (tags[i] == tag) return;
    if (tag_count < kSpanTags) tags[tag_count] = tag;
    tag_count = std::min(tag_count + 1, kSpanTags + 1);
  }
};

class PlaneBlocks {
 public:
  struct Stats {
    std::size_t blocks[3] = {0, 0, 0};  // per axis
    std::size_t entries = 0;            // plane listings in all blocks
    std::size_t empty = 0;              // blocks with no plane
    std::size_t longest = 0;            // most elements in one listing
    std::size_t marked = 0;             // blocks marked (holding BSP triangles)
    std::size_t gathered_big = 0;       // blocks of more than kGathered listings that the lanes test
    double mean_free_path = 0.0;        // 4 V / S over the grid (see most_gathered_)
  };

  PlaneBlocks() = default;
  // `boxes` grouped by (axis, plane), planes of each axis in increasing coordinate; about `target_blocks`
  // near-cubic blocks over their bounds, with at most one layer per `planes_per_layer` planes along each axis
  // (0: no such limit). `area` is the total area of the surfaces the boxes bound (for the mean free path).
  PlaneBlocks(std::span<const PlaneBox> boxes, std::size_t target_blocks, double planes_per_layer,
              bool lanes = true, double area = 0.0);

  // Calls visit(axis, first, count, t, pu, pv) for each listed plane the ray crosses with tmin < t < limit,
  // where (pu, pv) is the crossing point in the plane's frame and lies within the bounds of the plane's
  // elements in the block, which are items()[first, first + count); in increasing t when kOrdered, else block
  // by block front to back and axis by axis in increasing t within a block (a plane on a block edge
  // may come twice). `limit` may shrink during the walk (closest hit). visit returns true to stop.
  // prefetch(first, end) is called with ranges of items before the walk visits them, so that the owner can
  // start loading its elements while the walk reads the listings (two memory latencies overlap instead of
  // adding up): a merged block's whole range on entering it, a gathered block's first four crossed
  // listings' as soon as the kernel has found them.
  // kOrdered false (any-hit queries, where order does not matter) walks each axis' listings on their own
  // instead of merging the three: the merge's branches cost more than they save there (E1M1 and DM1
  // occlusion rays 11-19 % faster); closest hits keep the merge, which stops at the first hit (the office,
  // one block of many planes, ran 7-40 % slower without it).
  // With lanes (BlockSizing::lanes, AVX-512), a block of at most kGathered listings is instead tested all at
  // once and its crossings visited in the same order; so is a block of up to kGatheredMax listings where
  // rays usually cross blocks (most_gathered_); other blocks (the office's single block of 18) keep the
  // merge, which stops at the first hit, where testing every listing cost its primary rays 15-26 %.
  //
  // `marked` (may be null) gathers the span of t over the marked blocks the walk passed (kOrdered: only
  // where it passed their marked boxes) and their tags: a ray can meet what was marked (the BSP's
  // triangles) only there. It is complete only when the walk was not stopped by visit.
  template <bool kOrdered, class Visit, class Prefetch>
  void walk(const model::Vec3& o, const model::Vec3& d, double tmin, const double& limit, Visit&& visit,
            Prefetch&& prefetch, MarkedSpan* marked = nullptr) const;

  // Marks every block that the triangle (a, b, c) reaches within the margin, and grows the block's marked
  // box by the bounds of the triangle's part inside the block: a walk counts a marked block only where the
  // ray passes that box. Returns false when the triangle is not inside the grid (a walk can then not tell
  // where a ray meets it), true otherwise.
  bool mark(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c);

  // Tags each marked block with f(lo, hi) of its marked box: the walk gathers the tags of the marked blocks
  // it passes (MarkedSpan::tags). The caster tags them with the BSP node enclosing the box.
  template <class F>
  void tag_marks(F&& f) {
    for (MarkBox& m : marks_)
      m.tag = f(model::Vec3(m.lo[0], m.lo[1], m.lo[2]), model::Vec3(m.hi[0], m.hi[1], m.hi[2]));
  }

  [[nodiscard]] const Stats& stats() const { return stats_; }
  // Whether the walk tests listings eight at a time (BlockSizing::lanes on a CPU with AVX-512).
  [[nodiscard]] bool uses_lanes() const { return !lanes_.coord.empty(); }
  // Element indices (PlaneBox::item) of every listing, block by block: each listing's elements are the ones
  // of its plane whose bounds reach the block, so a crossing tests only those (the plane's 2D grid), in
  // increasing PlaneBox::u0, so that a crossing can stop at the first one starting beyond its point.
  [[nodiscard]] const std::vector<std::uint32_t>& items() const { return items_; }
  [[nodiscard]] std::size_t memory_bytes() const;
  // Block edges along `axis`, in the owner's (local) frame: for tests that aim rays at them.
  [[nodiscard]] const std::vector<double>& edges(int axis) const { return edges_[axis]; }

 private:
  struct Entry {  // one plane's elements inside one block
    double coord;
    double u0, u1, v0, v1;
    std::uint32_t first, count;  // into items_
  };
  struct Block {  // axis k's entries are [end[k - 1], end[k]) with end[-1] = first
    std::uint32_t first;
    std::uint32_t end[3];
    std::uint32_t items_first, items_end;  // the items of all its entries, for prefetching
    std::uint32_t mark;                    // 1 + its index in marks_, 0 when not marked (see mark())
  };
  struct MarkBox {  // the bounds of the marked triangles' parts inside a block, widened by the margin
    double lo[3], hi[3];
    std::uint32_t tag;
  };

  [[nodiscard]] std::size_t block_index(const int idx[3]) const {
    return (static_cast<std::size_t>(idx[2]) * n_[1] + idx[1]) * n_[0] + idx[0];
  }
  // Calls f(block index) for every block that the box [lo, hi] reaches within the margin.
  template <class F>
  void for_blocks_meeting(const model::Vec3& lo, const model::Vec3& hi, F&& f) const;
  // The layer of blocks along axis k whose edges (in t, as the walk computes them) enclose t, searched from
  // the layer holding coordinate `near` (any estimate of the ray's coordinate at t).
  [[nodiscard]] int layer_at(int k, double ok, double dk, double inv, double t, double near) const;

  std::vector<double> edges_[3];  // n_[k] + 1 block edges along each axis
  int n_[3] = {0, 0, 0};
  double per_metre_[3] = {0.0, 0.0, 0.0};  // layers per metre
  std::vector<Block> blocks_;
  std::vector<Entry> entries_;
  std::vector<MarkBox> marks_;
  CrossingLanes lanes_;  // entries_' coordinates and bounds as arrays; empty when not used
  std::vector<std::uint32_t> items_;
  double margin_ = 0.0;  // kBlockMargin times the grid's diagonal
  // The most listings a block may have for the lanes to test it: 0 without lanes, else kGathered, or
  // kGatheredMax where rays usually cross a block rather than end in it. The merge stops at the first hit, so
  // it wins where rays end inside the block they are in; the lanes test every listing of a block at once, so
  // they win where rays cross it. Which one a model's rays do is told by the mean free path, 4 V / S for
  // surfaces of total area S in a volume V (Cauchy's mean chord length), against the blocks' side: the
  // office's one block (28 m) is ten times its 2.9 m, and the lanes cost its closest hits 10-26 %; E1M1's
  // blocks (5.4 m) are a third of its 15 m, and the lanes gained its rays from surfaces 12-13 % (walk bench
  // rays, docs/RAYCAST.md "How the axial caster works").
  std::uint32_t most_gathered_ = 0;
  Stats stats_;
};

[[gnu::always_inline]] inline int PlaneBlocks::layer_at(int k, double ok, double dk, double inv, double t,
                                                        double near) const {
  const std::vector<double>& e = edges_[k];
  const int n = n_[k];
  if (dk == 0.0) {  // parallel to the layers: the origin's layer throughout
    const auto it = std::upper_bound(e.begin() + 1, e.end() - 1, ok);
    return static_cast<int>(it - (e.begin() + 1));
  }
  int i = static_cast<int>(
      std::clamp((near - e[0]) * per_metre_[k], 0.0, static_cast<double>(n - 1)));  // estimate, then
  if (dk > 0.0) {  // settle on the layer the t formula agrees with
    while (i > 0 && (e[i] - ok) * inv > t) --i;
    while (i < n - 1 && (e[i + 1] - ok) * inv < t) ++i;
  } else {
    while (i < n - 1 && (e[i + 1] - ok) * inv > t) ++i;
    while (i > 0 && (e[i] - ok) * inv < t) --i;
  }
  return i;
}

template <bool kOrdered, class Visit, class Prefetch>
void PlaneBlocks::walk(const model::Vec3& origin, const model::Vec3& dir, double tmin, const double& limit,
                       Visit&& visit, Prefetch&& prefetch, MarkedSpan* marked) const {
  if (blocks_.empty()) return;
  // Plain arrays: glm's operator[] with a run-time axis is a switch, three branches per use.
  const double o[3] = {origin.x, origin.y, origin.z};
  const double d[3] = {dir.x, dir.y, dir.z};
  double inv[3] = {0.0, 0.0, 0.0};
  // Where the first block is looked for: the ray's point at tmin, which for a ray starting inside the grid
  // (t0 == tmin below, the usual case) lies in it. Computed without the divisions and the clip, so the
  // first block's index, and the loads that follow, need not wait for them (the settling comparisons that
  // do wait are predicted to hold): the clip's chain of divisions, minima and maxima was most of a ray's
  // fixed cost.
  double near[3] = {o[0] + tmin * d[0], o[1] + tmin * d[1], o[2] + tmin * d[2]};
  double t0 = tmin, t1 = limit;
  for (int k = 0; k < 3; ++k) {
    const std::vector<double>& e = edges_[k];
    if (d[k] == 0.0) {
      if (!(o[k] >= e.front() && o[k] <= e.back())) return;
      continue;
    }
    inv[k] = 1.0 / d[k];
    const double ta = (e.front() - o[k]) * inv[k], tb = (e.back() - o[k]) * inv[k];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  if (!(t0 <= t1)) return;
  if (t0 != tmin)  // starting outside the grid: look from where the ray enters it
    for (int k = 0; k < 3; ++k) near[k] = o[k] + t0 * d[k];

  int idx[3], step[3], stop[3];
  double next[3];  // t at which the ray leaves the current layer along each axis
  for (int k = 0; k < 3; ++k) {
    idx[k] = layer_at(k, o[k], d[k], inv[k], t0, near[k]);
    step[k] = d[k] > 0.0 ? 1 : -1;
    stop[k] = d[k] > 0.0 ? n_[k] : -1;
    next[k] = d[k] == 0.0 ? INFINITY : (edges_[k][idx[k] + (d[k] > 0.0 ? 1 : 0)] - o[k]) * inv[k];
  }

  // A point the walk places in a block lies in it up to rounding; the margin in t covers that (margin / |d|
  // <= margin / max |d_k|).
  const double slack = marked ? margin_ / std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}) : 0.0;
  double t_enter = t0;
  for (;;) {
    const Block& b = blocks_[block_index(idx)];
    // Start loading what the block's listings test reads before the marked box is tested: all of the lanes'
    // arrays over the block's listings (the crossed listings' elements follow once the kernel has found
    // them), or for the merge the first listings and the first lines of the block's elements.
    const bool listed = b.end[2] != b.first;
    const bool gathered = listed && b.end[2] - b.first <= most_gathered_;
    if (gathered) {
      lanes_.prefetch(b.first, b.end[2]);
    } else if (listed) {
      __builtin_prefetch(&entries_[b.first]);
      prefetch(b.items_first, b.items_end);
    }
    const double t_exit = std::min({next[0], next[1], next[2]});
    if (marked && b.mark != 0) {
      // The ray's interval in the block's marked box, widened by the slack. An any-hit walk (not ordered)
      // takes the whole block: there the box tests cost more than the BSP searches they saved (E1M1, DM1
      // and house occlusion rays 4-6 % faster without them).
      const MarkBox& m = marks_[b.mark - 1];
      double ta = t_enter - slack, tb = std::min(t_exit, limit) + slack;
      if constexpr (kOrdered)
        for (int k = 0; k < 3; ++k) {
          if (d[k] == 0.0) {  // parallel: inside the box's slab throughout or never
            if (!(o[k] >= m.lo[k] && o[k] <= m.hi[k])) tb = -INFINITY;
            continue;
          }
          const double n = (m.lo[k] - o[k]) * inv[k], f = (m.hi[k] - o[k]) * inv[k];
          ta = std::max(ta, std::min(n, f));
          tb = std::min(tb, std::max(n, f));
        }
      if (ta <= tb) {
        marked->add_tag(m.tag);
        marked->first = std::min(marked->first, ta - slack);
        marked->last = std::max(marked->last, tb + slack);
      }
    }
    if (listed) {
      if (gathered) {
        // Every listing the ray crosses inside its bounds, gathered eight at a time (crossing_lanes.hpp),
        // then visited in increasing t: the merge's order, without its unpredictable branches.
        double ct[kGatheredMax + kCrossingSlack], cu[kGatheredMax + kCrossingSlack],
            cv[kGatheredMax + kCrossingSlack];
        std::uint32_t ci[kGatheredMax + kCrossingSlack];
        std::uint64_t items[kGatheredMax + kCrossingSlack];
        const Crossings out{ct, cu, cv, ci, items};
        const int n =
            gather_crossings(lanes_, b.first, b.end, {o, d, inv, t_enter, tmin, t_exit, limit}, out);
        // The elements of the first crossings start loading now, not after each one's listing is read.
        for (int c = 0; c < std::min(n, 4); ++c) {
          const auto first = static_cast<std::uint32_t>(items[c]);
          prefetch(first, first + static_cast<std::uint32_t>(items[c] >> 32));
        }
        for (int done = 0; done < n; ++done) {
          int i = done;  // the next crossing: least t, the earlier listing on equal t (lower axis first)
          if constexpr (kOrdered) {
            for (int m = done + 1; m < n; ++m) i = ct[m] < ct[i] ? m : i;
            if (!(ct[i] < limit)) break;
            std::swap(ct[i], ct[done]);
            std::swap(cu[i], cu[done]);
            std::swap(cv[i], cv[done]);
            std::swap(ci[i], ci[done]);
            std::swap(items[i], items[done]);
            i = done;
          }
          const std::uint32_t j = ci[i];
          const int k = j < b.end[0] ? 0 : j < b.end[1] ? 1 : 2;
          if (visit(k, static_cast<std::uint32_t>(items[i]), static_cast<std::uint32_t>(items[i] >> 32),
                    ct[i], cu[i], cv[i]))
            return;
        }
      } else if constexpr (!kOrdered) {
        // Each axis' listings in increasing t (backwards when the ray runs down the axis), from the block's
        // entry to its exit or the limit.
        std::uint32_t begin = b.first;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t lo = begin, hi = b.end[k];
          begin = hi;
          if (lo == hi || d[k] == 0.0) continue;
          const int u = kPlaneU[k], v = kPlaneV[k];
          const bool up = d[k] > 0.0;
          for (std::uint32_t n = 0; n < hi - lo; ++n) {
            const Entry& en = entries_[up ? lo + n : hi - 1 - n];
            const double t = (en.coord - o[k]) * inv[k];
            if (t < t_enter || !(t > tmin)) continue;
            if (!(t <= t_exit) || !(t < limit)) break;
            const double pu = o[u] + t * d[u];
            const double pv = o[v] + t * d[v];
            if (pu < en.u0 || pu > en.u1 || pv < en.v0 || pv > en.v1) continue;
            if (visit(k, en.first, en.count, t, pu, pv)) return;
          }
        }
      } else {
        // Per axis: the next entry the ray crosses in this block, and its t.
        std::uint32_t cur[3], end[3];
        double ct[3];
        std::uint32_t begin = b.first;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t lo = begin, hi = b.end[k];
          begin = hi;
          ct[k] = INFINITY;
          cur[k] = end[k] = 0;
          if (lo == hi || d[k] == 0.0) continue;
          if (d[k] > 0.0) {
            std::uint32_t j = lo;
            while (j < hi && (entries_[j].coord - o[k]) * inv[k] < t_enter) ++j;
            cur[k] = j;
            end[k] = hi;
          } else {  // walk the list backwards: cur counts one past the entry
            std::uint32_t j = hi;
            while (j > lo && (entries_[j - 1].coord - o[k]) * inv[k] < t_enter) --j;
            cur[k] = j;
            end[k] = lo;
          }
          if (cur[k] != end[k]) ct[k] = (entries_[d[k] > 0.0 ? cur[k] : cur[k] - 1].coord - o[k]) * inv[k];
        }
        for (;;) {
          const int k = ct[0] <= ct[1] ? (ct[0] <= ct[2] ? 0 : 2) : (ct[1] <= ct[2] ? 1 : 2);
          const double t = ct[k];
          if (!(t <= t_exit) || !(t < limit)) break;
          const Entry& en = entries_[d[k] > 0.0 ? cur[k] : cur[k] - 1];
          cur[k] = d[k] > 0.0 ? cur[k] + 1 : cur[k] - 1;
          ct[k] = cur[k] != end[k] ? (entries_[d[k] > 0.0 ? cur[k] : cur[k] - 1].coord - o[k]) * inv[k]
                                   : INFINITY;
          if (!(t > tmin)) continue;
          const double pu = o[kPlaneU[k]] + t * d[kPlaneU[k]];
          const double pv = o[kPlaneV[k]] + t * d[kPlaneV[k]];
          if (pu < en.u0 || pu > en.u1 || pv < en.v0 || pv > en.v1) continue;
          if (visit(k, en.first, en.count, t, pu, pv)) return;
        }
      }
    }
    const int k = next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2) : (next[1] <= next[2] ? 1 : 2);
    if (!(next[k] < limit)) return;
    t_enter = next[k];
    idx[k] += step[k];
    if (idx[k] == stop[k]) return;
    next[k] = (edges_[k][idx[k] + (d[k] > 0.0 ? 1 : 0)] - o[k]) * inv[k];
  }
}

}  // namespace walk::compiler
