#pragma once
// Several plane listings tested at once. A ray that starts at a random surface point (radiosity, occlusion)
// makes the block walk's branches unpredictable: where its start lies among a block's sorted planes, which
// axis the merge takes next, whether it passes a listing's bounds. On the house, whose structure sits in
// L1, sorting the same rays by origin made them twice as fast, so those mispredictions, not memory, set
// the speed. Here a block's listings are tested eight at a time with AVX-512 and the ones the ray crosses
// inside their bounds are compressed into a short list, with no branch per listing.
//
// The kernel does the walk's own arithmetic, t = (coord - o) * inv and p = o + t * d, as separate IEEE
// operations (this file is compiled with -ffp-contract=off), so it picks exactly the listings the scalar
// walk would.
#include <cstdint>
#include <vector>

namespace walk::compiler {

// The listings' coordinates and in-plane bounds, one array each, so eight load at once.
// Each listing's items too (first | count << 32), so that a crossing carries its range out of the kernel and
// the walk can start loading the elements it will test without first reading the listing's record.
struct CrossingLanes {
  std::vector<double> coord, u0, u1, v0, v1;
  std::vector<std::uint64_t> items;
  void push_back(double c, double a0, double a1, double b0, double b1, std::uint32_t first = 0,
                 std::uint32_t count = 0) {
    coord.push_back(c);
    u0.push_back(a0);
    u1.push_back(a1);
    v0.push_back(b0);
    v1.push_back(b1);
    items.push_back(first | static_cast<std::uint64_t>(count) << 32);
  }
  [[nodiscard]] std::size_t memory_bytes() const {
    return 5 * coord.capacity() * sizeof(double) + items.capacity() * sizeof(std::uint64_t);
  }
  // Starts loading listings [first, end) of every array (a cache line holds eight).
  void prefetch(std::uint32_t first, std::uint32_t end) const {
    for (std::uint32_t j = first; j < end; j += 8) {
      for (const auto* a : {&coord, &u0, &u1, &v0, &v1}) __builtin_prefetch(a->data() + j);
      __builtin_prefetch(items.data() + j);
    }
  }
};

// One ray against one block's listings: origin, direction and its inverse (0 along an axis the ray does not
// move on), and the interval of t the walk accepts: t_enter <= t, tmin < t, t <= t_exit, t < limit.
struct CrossingRay {
  const double* o;
  const double* d;
  const double* inv;
  double t_enter, tmin, t_exit, limit;
};

// True when this CPU runs the AVX-512 kernel (AVX-512 F and VL).
bool crossing_lanes_available();

// Where gather_crossings writes: per crossing its t, its point in the plane, its listing's index and items.
// Each array needs room for kCrossingSlack entries past the block's listing count: the kernel stores whole
// vectors (compressed in registers) rather than branching on whether a group of eight crossed anything.
inline constexpr std::uint32_t kCrossingSlack = 8;
struct Crossings {
  double* t;
  double* pu;
  double* pv;
  std::uint32_t* index;
  std::uint64_t* items;  // the listing's CrossingLanes::items
};

// Writes every listing of one block (axis k's are [end[k - 1], end[k]) with end[-1] = first) that the ray
// crosses inside its bounds and interval to `out`, in index order; returns how many. Only call when
// crossing_lanes_available().
int gather_crossings(const CrossingLanes& lanes, std::uint32_t first, const std::uint32_t end[3],
                     const CrossingRay& ray, const Crossings& out);

}  // namespace walk::compiler
