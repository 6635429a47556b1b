#include "compiler/raycast/plane_blocks.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

constexpr int kMaxBlocksPerAxis = 256;

// Layers [first, last] of `edges` whose extent, widened by `margin`, meets [lo, hi].
std::pair<int, int> layers_meeting(const std::vector<double>& edges, double lo, double hi, double margin) {
  const int n = static_cast<int>(edges.size()) - 1;
  int first = static_cast<int>(std::lower_bound(edges.begin(), edges.end(), lo - margin) - edges.begin()) - 1;
  int last = static_cast<int>(std::upper_bound(edges.begin(), edges.end(), hi + margin) - edges.begin()) - 1;
  return {std::clamp(first, 0, n - 1), std::clamp(last, 0, n - 1)};
}

// Bounds of the part of the convex polygon inside the box [lo, hi] (Sutherland-Hodgman against its six
// faces); false when none is. The clipped corners carry rounding of a few ulp, which the caller's margin
// covers.
bool part_bounds(std::vector<model::Vec3> poly, const model::Vec3& lo, const model::Vec3& hi,
                 model::Vec3& part_lo, model::Vec3& part_hi) {
  std::vector<model::Vec3> kept;
  for (int k = 0; k < 3 && !poly.empty(); ++k)
    for (const double sign : {1.0, -1.0}) {  // keep sign * (p[k] - bound) >= 0
      const double bound = sign > 0.0 ? lo[k] : hi[k];
      kept.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const model::Vec3& p = poly[i];
        const model::Vec3& q = poly[(i + 1) % poly.size()];
        const double dp = sign * (p[k] - bound), dq = sign * (q[k] - bound);
        if (dp >= 0.0) kept.push_back(p);
        if ((dp < 0.0) != (dq < 0.0)) {
          model::Vec3 x = p + (q - p) * (dp / (dp - dq));
          x[k] = bound;  // exactly on the face, whatever the rounding of the interpolation
          kept.push_back(x);
        }
      }
      poly.swap(kept);
      if (poly.empty()) break;
    }
  if (poly.empty()) return false;
  part_lo = part_hi = poly[0];
  for (const model::Vec3& p : poly) {
    part_lo = glm::min(part_lo, p);
    part_hi = glm::max(part_hi, p);
  }
  return true;
}

}  // namespace

PlaneBlocks::PlaneBlocks(std::span<const PlaneBox> boxes, std::size_t target_blocks, double planes_per_layer,
                         bool lanes, double area) {
  if (boxes.empty()) return;
  model::Vec3 lo(INFINITY), hi(-INFINITY);
  for (const PlaneBox& b : boxes) {
    const int k = b.axis, u = kPlaneU[k], v = kPlaneV[k];
    lo[k] = std::min(lo[k], b.coord);
    hi[k] = std::max(hi[k], b.coord);
    lo[u] = std::min(lo[u], b.u0);
    hi[u] = std::max(hi[u], b.u1);
    lo[v] = std::min(lo[v], b.v0);
    hi[v] = std::max(hi[v], b.v1);
  }
  for (int k = 0; k < 3; ++k)  // an axis no plane spans (a flat model) still gets one layer
    if (!(lo[k] <= hi[k])) lo[k] = hi[k] = 0.0;
  const double margin = kBlockMargin * std::max(glm::length(hi - lo), 1.0);
  margin_ = margin;
  lo -= model::Vec3(margin);
  hi += model::Vec3(margin);

  // Near-cubic blocks: side s with prod(extent / s) = target over the axes longer than s (a flat model, or a
  // thin slab of one, gets a single layer along its thin axis and the target spread over the others).
  const model::Vec3 extent = hi - lo;
  const double target = static_cast<double>(std::max<std::size_t>(target_blocks, 1));
  bool thin[3] = {false, false, false};
  double side = 0.0;
  for (int pass = 0; pass < 3; ++pass) {
    double volume = 1.0;
    int dims = 0;
    for (int k = 0; k < 3; ++k)
      if (!thin[k]) {
        volume *= extent[k];
        ++dims;
      }
    if (dims == 0) break;
    side = std::pow(volume / target, 1.0 / dims);
    bool changed = false;
    for (int k = 0; k < 3; ++k)
      if (!thin[k] && extent[k] < side) thin[k] = changed = true;
    if (!changed) break;
  }
  // A layer of blocks pays only when the walk would otherwise cross several planes of that axis in it.
  std::size_t planes[3] = {0, 0, 0};
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (i == 0 || boxes[i - 1].axis != boxes[i].axis || boxes[i - 1].plane != boxes[i].plane)
      ++planes[boxes[i].axis];
  for (int k = 0; k < 3; ++k) {
    const double most = planes_per_layer > 0.0
                            ? std::max(1.0, std::floor(static_cast<double>(planes[k]) / planes_per_layer))
                            : static_cast<double>(kMaxBlocksPerAxis);
    n_[k] = thin[k] ? 1
                    : static_cast<int>(std::clamp(std::round(extent[k] / side), 1.0,
                                                  std::min(most, static_cast<double>(kMaxBlocksPerAxis))));
    edges_[k].resize(n_[k] + 1);
    for (int i = 0; i <= n_[k]; ++i) edges_[k][i] = lo[k] + extent[k] * i / n_[k];
    edges_[k][n_[k]] = hi[k];
    stats_.blocks[k] = n_[k];
    per_metre_[k] = n_[k] / extent[k];
  }

  // Listings (block, entry), gathered plane by plane; `slot` remembers the current plane's entry per block.
  const std::size_t count = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
  std::vector<std::uint32_t> slot(count, UINT32_MAX);
  std::vector<std::uint32_t> touched;
  struct Listing {
    std::uint32_t block;
    Entry entry;
    std::vector<std::uint32_t> items;
  };
  std::vector<Listing> listed;
  std::vector<std::uint8_t> axis_of;
  auto flush = [&] {
    for (const std::uint32_t blk : touched) slot[blk] = UINT32_MAX;
    touched.clear();
  };
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const PlaneBox& b = boxes[i];
    if (i > 0 && (boxes[i - 1].axis != b.axis || boxes[i - 1].plane != b.plane)) flush();
    const int k = b.axis, u = kPlaneU[k], v = kPlaneV[k];
    model::Vec3 box_lo, box_hi;
    box_lo[k] = box_hi[k] = b.coord;
    box_lo[u] = b.u0;
    box_hi[u] = b.u1;
    box_lo[v] = b.v0;
    box_hi[v] = b.v1;
    for_blocks_meeting(box_lo, box_hi, [&](std::size_t block) {
      const auto blk = static_cast<std::uint32_t>(block);
      if (slot[blk] == UINT32_MAX) {
        slot[blk] = static_cast<std::uint32_t>(listed.size());
        touched.push_back(blk);
        listed.push_back({blk, {b.coord, b.u0, b.u1, b.v0, b.v1, 0, 0}, {b.item}});
        axis_of.push_back(static_cast<std::uint8_t>(k));
      } else {
        listed[slot[blk]].items.push_back(b.item);
        Entry& e = listed[slot[blk]].entry;
        e.u0 = std::min(e.u0, b.u0);
        e.u1 = std::max(e.u1, b.u1);
        e.v0 = std::min(e.v0, b.v0);
        e.v1 = std::max(e.v1, b.v1);
      }
    });
  }

  // Counting sort by (block, axis); stable, so each axis' entries stay in increasing coordinate.
  std::vector<std::uint32_t> start(count * 3 + 1, 0);
  for (std::size_t j = 0; j < listed.size(); ++j) ++start[listed[j].block * 3 + axis_of[j] + 1];
  for (std::size_t c = 0; c < count * 3; ++c) start[c + 1] += start[c];
  blocks_.resize(count);  // value-initialised: an empty block's ranges are all zero
  for (std::size_t blk = 0; blk < count; ++blk) {
    blocks_[blk].first = start[blk * 3];
    for (int k = 0; k < 3; ++k) blocks_[blk].end[k] = start[blk * 3 + k + 1];
    if (blocks_[blk].end[2] == blocks_[blk].first) ++stats_.empty;
  }
  std::vector<std::uint32_t> order(listed.size());
  for (std::size_t j = 0; j < listed.size(); ++j) order[start[listed[j].block * 3 + axis_of[j]]++] = j;
  entries_.reserve(listed.size());
  // A listing's items in increasing u0, so that a visit can stop at the first element starting beyond its
  // point (a plane diced into patches lists rows of them). AxialPlanes::walk relies on this order.
  std::vector<double> item_u0;
  for (const PlaneBox& b : boxes) {
    if (b.item >= item_u0.size()) item_u0.resize(b.item + 1, 0.0);
    item_u0[b.item] = b.u0;
  }
  for (const std::uint32_t j : order) {  // items laid out in entry order: a block's reads are close together
    std::stable_sort(listed[j].items.begin(), listed[j].items.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return item_u0[a] < item_u0[b]; });
    Entry e = listed[j].entry;
    e.first = static_cast<std::uint32_t>(items_.size());
    e.count = static_cast<std::uint32_t>(listed[j].items.size());
    stats_.longest = std::max<std::size_t>(stats_.longest, e.count);
    items_.insert(items_.end(), listed[j].items.begin(), listed[j].items.end());
    entries_.push_back(e);
  }
  for (std::size_t blk = 0; blk < count; ++blk)
    if (blocks_[blk].end[2] != blocks_[blk].first) {
      blocks_[blk].items_first = entries_[blocks_[blk].first].first;
      blocks_[blk].items_end =
          entries_[blocks_[blk].end[2] - 1].first + entries_[blocks_[blk].end[2] - 1].count;
    }
  stats_.entries = entries_.size();
  if (lanes && crossing_lanes_available())
    for (const Entry& e : entries_) lanes_.push_back(e.coord, e.u0, e.u1, e.v0, e.v1, e.first, e.count);
  // Rays cross a block more often than they end in it when its side is under the mean free path (see
  // most_gathered_); a thin axis' single layer does not count towards the side.
  stats_.mean_free_path = area > 0.0 ? 4.0 * extent.x * extent.y * extent.z / area : 0.0;
  double block_volume = 1.0;
  int dims = 0;
  for (int k = 0; k < 3; ++k)
    if (!thin[k]) {
      block_volume *= extent[k] / n_[k];
      ++dims;
    }
  const double block_side = dims > 0 ? std::pow(block_volume, 1.0 / dims) : 0.0;
  most_gathered_ = !uses_lanes() ? 0 : block_side <= stats_.mean_free_path ? kGatheredMax : kGathered;
  for (const Block& b : blocks_)
    if (b.end[2] - b.first > kGathered && b.end[2] - b.first <= most_gathered_) ++stats_.gathered_big;
}

bool PlaneBlocks::mark(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c) {
  if (blocks_.empty()) return false;
  const model::Vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  for (int k = 0; k < 3; ++k)
    if (!(lo[k] >= edges_[k].front() && hi[k] <= edges_[k].back())) return false;
  const std::vector<model::Vec3> triangle = {a, b, c};
  for_blocks_meeting(lo, hi, [&](std::size_t block) {
    const std::size_t i0 = block % n_[0], i1 = block / n_[0] % n_[1], i2 = block / n_[0] / n_[1];
    const model::Vec3 block_lo(edges_[0][i0], edges_[1][i1], edges_[2][i2]);
    const model::Vec3 block_hi(edges_[0][i0 + 1], edges_[1][i1 + 1], edges_[2][i2 + 1]);
    model::Vec3 part_lo, part_hi;
    if (!part_bounds(triangle, block_lo - margin_, block_hi + margin_, part_lo, part_hi)) return;
    Block& blk = blocks_[block];
    if (blk.mark == 0) {
      marks_.push_back({{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, 0});
      blk.mark = static_cast<std::uint32_t>(marks_.size());
      ++stats_.marked;
    }
    MarkBox& m = marks_[blk.mark - 1];
    for (int k = 0; k < 3; ++k) {
      m.lo[k] = std::min(m.lo[k], part_lo[k] - margin_);
      m.hi[k] = std::max(m.hi[k], part_hi[k] + margin_);
    }
  });
  return true;
}

template <class F>
void PlaneBlocks::for_blocks_meeting(const model::Vec3& lo, const model::Vec3& hi, F&& f) const {
  std::pair<int, int> range[3];
  for (int k = 0; k < 3; ++k) range[k] = layers_meeting(edges_[k], lo[k], hi[k], margin_);
  int idx[3];
  for (idx[2] = range[2].first; idx[2] <= range[2].second; ++idx[2])
    for (idx[1] = range[1].first; idx[1] <= range[1].second; ++idx[1])
      for (idx[0] = range[0].first; idx[0] <= range[0].second; ++idx[0]) f(block_index(idx));
}

std::size_t PlaneBlocks::memory_bytes() const {
  return blocks_.capacity() * sizeof(Block) + entries_.capacity() * sizeof(Entry) +
         items_.capacity() * sizeof(std::uint32_t) + marks_.capacity() * sizeof(MarkBox) +
         lanes_.memory_bytes() +
         (edges_[0].capacity() + edges_[1].capacity() + edges_[2].capacity()) * sizeof(double);
}

}  // namespace walk::compiler
