#include "compiler/visibility/hidden_proof.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "compiler/visibility/trace_through_glass.hpp"
#include "compiler/visibility/vis_items.hpp"

namespace walk::compiler {
namespace {

Box bounds_of(const Winding& w) {
  Box b{w.front(), w.front()};
  for (const auto& p : w) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

// The viewer region is the cell this far (metres) inside its faces: walls, floors and ceilings lie in the
// cells' faces, and an eye in a wall's plane sees past the wall's edge-on polygons. The renderer's near
// plane (5 cm) already clips a wall the eye comes this close to, and walking keeps a body radius off walls.
constexpr double kViewerInset = 1e-4;

Box inset(Box b) {
  for (int a = 0; a < 3; ++a) {
    const double m = std::min(kViewerInset, 0.25 * (b.max[a] - b.min[a]));
    b.min[a] += m;
    b.max[a] -= m;
  }
  return b;
}

int longest_axis(const model::Vec3& size) {
  return size.x >= size.y ? (size.x >= size.z ? 0 : 2) : (size.y >= size.z ? 1 : 2);
}

}  // namespace

int proof_allowance(std::size_t triangles, double mean_triangles, bool cluster, int proof_pairs,
                    int least_pairs) {
  const int most = std::max(0, proof_pairs);
  const int least = std::clamp(least_pairs, 0, most);
  if (cluster) return least;
  if (!(mean_triangles > 0.0)) return most;  // also NaN
  const double share = std::min(1.0, double(triangles) / mean_triangles);
  return std::clamp(static_cast<int>(std::lround(most * share)), least, most);
}

HiddenProver::HiddenProver(const std::vector<VisPolygon>& polygons, const RayCaster& caster,
                           bool cull_back_faces)
    : polygons_(polygons),
      caster_(caster),
      cull_back_faces_(cull_back_faces),
      planes_(polygons, cull_back_faces),
      glass_(polygons.size()),
      convex_(polygons.size()),
      planar_(polygons.size()) {
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    glass_[p] = polygons[p].glass;
    convex_[p] = fills_hull(polygons[p]);
    // In its plane, and no triangle turned the other way (a sliver the dicing flipped would be drawn from
    // the side the polygon's normal turns away from).
    bool planar = polygons[p].hull.size() >= 3 && glm::length(polygons[p].normal) > 0.0;
    for (const auto& t : polygons[p].triangles) {
      for (const auto& v : t)
        planar =
            planar && std::abs(glm::dot(polygons[p].normal, v - polygons[p].hull.front())) <= kShaftSlack;
      planar = planar && glm::dot(glm::cross(t[1] - t[0], t[2] - t[0]), polygons[p].normal) >= 0.0;
    }
    planar_[p] = planar;
  }
}

HiddenProver::Sight HiddenProver::sight(const model::Vec3& from, const model::Vec3& to,
                                        std::uint32_t target) const {
  Sight s;
  Ray ray;
  ray.origin = from;
  ray.dir = to - from;
  ray.tmin = 0.0;
  // Just past the target point, which lies in the target's plane: its hit rounds either side of t = 1.
  ray.tmax = 1.0 + 1e-9;
  for (int layer = 0; layer <= kMaxGlassLayers + 4; ++layer) {
    const RayHit h = caster_.closest(ray);
    if (!h.hit()) return s;
    const bool drawn = !cull_back_faces_ || h.front || glass_[h.polygon];
    if (h.polygon == target && drawn) {
      s.reaches = s.count == 0 && !s.opaque_unnamed;  // unless something drawn stood in front
      return s;
    }
    if (drawn && !glass_[h.polygon]) {
      // Blocked: go on only to name further planes that may hide the target from the whole pair.
      const int plane = planes_.plane_of(h.polygon);
      if (plane < 0) {
        s.opaque_unnamed = true;
      } else if (std::find(s.blockers, s.blockers + s.count, plane) == s.blockers + s.count) {
        s.blockers[s.count++] = plane;
        if (s.count == 4) return s;
      }
    }
    ray.tmin = h.t + tie_tolerance(ray.dir);
  }
  return s;
}

bool HiddenProver::faces_away(const Winding& source, std::uint32_t target) const {
  const VisPolygon& tp = polygons_[target];
  if (!cull_back_faces_ || !tp.opaque || !planar_[target]) return false;
  // planar_ holds only polygons whose every triangle faces along the polygon's normal: one plane decides.
  const Plane plane{tp.normal, -glm::dot(tp.normal, tp.hull.front())};
  for (const auto& s : source)
    if (plane.distance(s) > kShaftSlack) return false;
  return true;
}

bool HiddenProver::piece_meets_polygon(const Winding& piece, std::uint32_t target) const {
  if (convex_[target]) return true;
  const Box b = bounds_of(piece);
  for (const auto& t : polygons_[target].triangles) {
    const Box tb{glm::min(t[0], glm::min(t[1], t[2])), glm::max(t[0], glm::max(t[1], t[2]))};
    if (b.overlaps(tb, kShaftSlack)) return true;
  }
  return false;
}

// One proof's budget and outcome, shared by its branches.
struct HiddenProver::Search {
  std::uint32_t target;
  const ProofOptions& options;
  bool box_target = false;  // a detail cluster, proven hidden face by face of its box
  ProofStats stats;
  bool visible = false;  // a sight line reached the target: stop
  bool spent = false;    // the budget ran out: stop
  // Pieces waiting for a branch before them to be proven, each sure to take a pair of its own and each
  // needed for the proof to end hidden: once the pairs taken and these no longer fit the allowance, it
  // cannot (visible and undecided keep the item alike), so it stops there rather than at the allowance.
  std::uint64_t pending = 0;
  // Within a window's attempt (>0), whose failure falls back to splitting, a piece waiting is not needed
  // for the proof to end hidden, so none is counted.
  int trying_windows = 0;
  [[nodiscard]] bool stopped() const { return visible || spent; }
  // The verdict once the branches are done (`all`: every one proven hidden), counted into `out`.
  Verdict conclude(bool all, ProofStats* out) {
    const Verdict v = visible ? Verdict::Visible : all ? Verdict::Hidden : Verdict::Undecided;
    stats.tried = 1;
    (v == Verdict::Hidden ? stats.hidden : v == Verdict::Visible ? stats.visible : stats.undecided) = 1;
    if (out) out->add(stats);
    return v;
  }
};

namespace {

model::Vec3 centre_of(const Winding& w) {
  model::Vec3 c{0.0};
  for (const auto& v : w) c += v;
  return c / double(w.size());
}

}  // namespace

bool HiddenProver::hidden(const Piece& source, const Winding& dest, bool dest_is_target, bool top, int depth,
                          Search& search, std::optional<bool> takes) const {
  if (search.stopped()) return false;
  // Nothing to see: no pair.
  if (!(takes ? *takes : takes_a_pair(source, dest, dest_is_target, search.target))) return true;
  const std::uint64_t waiting = search.options.stop_early ? search.pending : 0;
  if (++search.stats.pairs + waiting > static_cast<std::uint64_t>(search.options.max_pairs)) {
    search.spent = true;
    return false;
  }
  if (!dest_is_target || !top) ++search.stats.windows;
  const Box sb = bounds_of(source.points);
  const Box db = bounds_of(dest);
  const bool looks_for_target = dest_is_target || search.box_target;
  // Between the pieces' vertex means: points of both, as both are convex.
  const Sight s =
      sight(centre_of(source.points), centre_of(dest), looks_for_target ? search.target : kNoTarget);
  // A sight line that gets through disproves "every segment is blocked": it meets the target, or meets
  // nothing on the way to a window's or a box face's centre (every point of those must be hidden; a piece of
  // a polygon's hull may hold none of the polygon). At the top the target is seen. Below (a window's side)
  // splitting could only find the same open line again, down to the depth limit or the allowance.
  const bool through = s.reaches || (!dest_is_target && s.count == 0 && !s.opaque_unnamed);
  if (through) {
    if (top) search.visible = true;
    return false;
  }
  // The first plane's shaft is kept: its open parts are the windows below.
  Shaft shaft;
  if (s.count > 0) {
    shaft = planes_.shaft(s.blockers[0], source.points, dest, false);
    if (shaft.blocked) return true;
  }
  for (int b = 1; b < s.count; ++b)
    if (planes_.blocks(s.blockers[b], source.points, dest)) return true;
  if (depth >= search.options.max_depth) return false;

  // Through the open parts of the first plane the sight line met, when they are a small part of its section.
  if (s.count > 0) {
    planes_.find_leaks(s.blockers[0], shaft);
    if (shaft.applies && !shaft.leaks.empty() &&
        shaft.leak_area <= search.options.window_fraction * shaft.section_area) {
      bool all = true;
      ++search.trying_windows;
      for (const Winding& window : shaft.leaks) {
        if (hidden(source, window, false, false, depth + 1, search)) continue;
        if (search.stopped()) break;
        // Only what a sight line from the source through the window reaches (else the window's side
        // would have to hide the target from the whole window, along lines that never come from the source).
        if (hidden({window, false}, reached_through(source.points, window, dest), dest_is_target, false,
                   depth + 1, search))
          continue;
        all = false;
        break;
      }
      --search.trying_windows;
      if (all && !search.stopped()) return true;
      if (search.stopped()) return false;
    }
  }

  // Split whichever piece is larger: a wide source sees round an occluder's edge, a long target reaches
  // past it.
  const model::Vec3 ss = sb.size(), ds = db.size();
  const int sa = longest_axis(ss), da = longest_axis(ds);
  if (ss[sa] >= ds[da]) {
    const double mid = 0.5 * (sb.min[sa] + sb.max[sa]);
    Piece a, b;
    if (source.box) {
      Box lo = sb, hi = sb;
      lo.max[sa] = hi.min[sa] = mid;
      a = {box_corners(lo), true};
      b = {box_corners(hi), true};
    } else {
      const Plane cut = axial_plane(sa, mid, 1.0);
      a = {clip_front(source.points, cut), false};
      b = {clip_front(source.points, cut.flipped()), false};
    }
    return both_hidden(a, dest, b, dest, dest_is_target, top, depth + 1, search);
  }
  const Plane cut = axial_plane(da, 0.5 * (db.min[da] + db.max[da]), 1.0);
  return both_hidden(source, clip_front(dest, cut), source, clip_front(dest, cut.flipped()), dest_is_target,
                     top, depth + 1, search);
}

bool HiddenProver::takes_a_pair(const Piece& source, const Winding& dest, bool dest_is_target,
                                std::uint32_t target) const {
  if (dest.size() < 3 || source.points.empty()) return false;  // nothing (or no area) to see
  return !dest_is_target || (piece_meets_polygon(dest, target) && !faces_away(source.points, target));
}

bool HiddenProver::both_hidden(const Piece& s1, const Winding& d1, const Piece& s2, const Winding& d2,
                               bool dest_is_target, bool top, int depth, Search& search) const {
  // Asked once: for the count of pieces waiting, then by the second piece's own proof.
  std::optional<bool> second_takes;
  if (search.trying_windows == 0) second_takes = takes_a_pair(s2, d2, dest_is_target, search.target);
  const std::uint64_t waits = second_takes.value_or(false) ? 1 : 0;
  search.pending += waits;
  const bool first = hidden(s1, d1, dest_is_target, top, depth, search);
  search.pending -= waits;
  return first && hidden(s2, d2, dest_is_target, top, depth, search, second_takes);
}

std::vector<Winding> HiddenProver::target_outlines(std::uint32_t target) const {
  const VisPolygon& tp = polygons_[target];
  // A sight line to any point of a cluster first crosses its box's surface: when no line reaches a face,
  // none reaches the cluster.
  return tp.detail ? box_faces(tp.box) : std::vector<Winding>{tp.hull};
}

bool HiddenProver::all_hidden(std::span<const Job> jobs, bool dest_is_target, Search& search) const {
  std::vector<char> pairs(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i)
    search.pending += pairs[i] = takes_a_pair(*jobs[i].source, jobs[i].dest, dest_is_target, search.target);
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    search.pending -= pairs[i];
    if (!hidden(*jobs[i].source, jobs[i].dest, dest_is_target, true, 0, search, pairs[i] != 0)) return false;
  }
  return true;
}

Verdict HiddenProver::prove(const Box& cell, std::span<const Exit> exits, std::uint32_t target,
                            const ProofOptions& options, ProofStats* stats) const {
  const VisPolygon& tp = polygons_[target];
  // Touching the cell: sight lines need not pass a portal.
  if (tp.box.overlaps(cell, kShaftSlack)) return prove_from_box(cell, target, options, stats);
  Search search{target, options, tp.detail, {}};
  // Each outline through each exit, all needed hidden.
  std::vector<Piece> sources;
  sources.reserve(exits.size());
  for (const Exit& e : exits) sources.push_back({e.hull, false});
  std::vector<Job> jobs;
  for (const Winding& outline : target_outlines(target))
    for (std::size_t k = 0; k < exits.size(); ++k) {
      // Only what lies beyond the portal is seen through it.
      Winding part = clip_front(outline, exits[k].out);
      if (part.size() >= 3 && exits[k].hull.size() >= 3) jobs.push_back({&sources[k], std::move(part)});
    }
  const bool all =
      (tp.detail || tp.hull.size() >= 3) && options.max_pairs > 0 && all_hidden(jobs, !tp.detail, search);
  return search.conclude(all, stats);
}

Verdict HiddenProver::prove_from_box(const Box& viewer, std::uint32_t target, const ProofOptions& options,
                                     ProofStats* stats) const {
  const VisPolygon& tp = polygons_[target];
  Search search{target, options, tp.detail, {}};
  const Piece source{box_corners(inset(viewer)), true};
  std::vector<Job> jobs;
  for (Winding& outline : target_outlines(target)) jobs.push_back({&source, std::move(outline)});
  const bool all =
      (tp.detail || tp.hull.size() >= 3) && options.max_pairs > 0 && all_hidden(jobs, !tp.detail, search);
  return search.conclude(all, stats);
}

}  // namespace walk::compiler
