#include "compiler/visibility/pvs_flow.hpp"

#include <algorithm>
#include <utility>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "compiler/visibility/vis_items.hpp"

namespace walk::compiler {
namespace {

// A flow past its budget gets this many times the budget again for the cell-level flow, whose steps test
// no items and prune far more.
constexpr std::uint64_t kCellFlowBudgetFactor = 10;
// A clipped portal or source narrower than this (metres; ten times kPlaneEpsilon) is the band clipping keeps
// along a plane: the sight lines through it lie in a plane that walls and floors meet edge on (the top of
// a ground-storey wall under the floor above), and they light no pixel. Followed, they let a flow creep
// along every floor plane of a building into every cell. Real cracks this thin are the samples' to find.
constexpr double kSliverWidth = 1e-4;

using Bits = std::vector<std::uint64_t>;  // one bit per cell

struct Directed {
  const Winding* winding;
  Plane plane;  // normal pointing into `to`
  std::uint32_t from;
  std::uint32_t to;
  // Cells a sight line through this portal might reach, one bit each (Quake vis's "mightsee"): a flood from
  // `to` through the portals that lie partly in front of this one and have this one partly behind them,
  // never re-entering `from`. A sight line through this portal and then others meets only such portals, so
  // a flow may go on through it only while some cell both it and every portal before it might reach is
  // not done yet.
  Bits might;
};

bool bit(const Bits& bits, std::uint32_t i) {
  return bits[i / 64] >> (i % 64) & 1;
}
void set_bit(Bits& bits, std::uint32_t i) {
  bits[i / 64] |= std::uint64_t(1) << (i % 64);
}

// Some point of `w` on the front side of `p`, counting points within kPlaneEpsilon as in front.
bool partly_in_front(const Winding& w, const Plane& p) {
  return std::any_of(w.begin(), w.end(),
                     [&](const model::Vec3& v) { return p.distance(v) >= -kPlaneEpsilon; });
}

// The directed portals of every cell and their might-see sets, built once and shared by every cell's flow.
struct FlowGraph {
  std::vector<std::vector<Directed>> out;        // per cell: portals sight lines may leave it through
  std::vector<std::vector<const Directed*>> in;  // per cell: portals sight lines may enter it through
  std::vector<std::vector<std::uint32_t>> cells_of_polygon;
  std::vector<std::vector<Occluder>> occluders;  // per cell (empty without occluder culling)
  std::vector<Winding> corners;                  // per item: a detail cluster's box corners (else empty)

  FlowGraph(const Partition& part, const PortalGraph& g, const std::vector<VisPolygon>& polygons,
            bool with_occluders)
      : out(part.cells.size()) {
    if (with_occluders) occluders = cell_occluders(part, polygons);
    corners.resize(polygons.size());
    for (std::size_t p = 0; p < polygons.size(); ++p)
      if (polygons[p].detail) corners[p] = box_corners(polygons[p].box);
    for (std::uint32_t c = 0; c < part.cells.size(); ++c)
      for (const auto id : g.cell_portals[c]) {
        const Portal& p = g.portals[id];
        if (!p.open_from(c)) continue;  // one-way, the other way
        out[c].push_back({&p.hull, p.out_of(c), c, p.back == c ? p.front : p.back, {}});
      }
    const std::size_t words = (part.cells.size() + 63) / 64;
    for (auto& cell_out : out)
      for (auto& d : cell_out) {
        d.might.assign(words, 0);
        std::vector<std::uint32_t> stack{d.to};
        set_bit(d.might, d.to);
        while (!stack.empty()) {
          const auto x = stack.back();
          stack.pop_back();
          for (const auto& e : out[x])
            if (e.to != d.from && !bit(d.might, e.to) && partly_in_front(*e.winding, d.plane) &&
                partly_in_front(*d.winding, e.plane.flipped())) {
              set_bit(d.might, e.to);
              stack.push_back(e.to);
            }
        }
      }
    in.resize(part.cells.size());
    for (const auto& cell_out : out)
      for (const auto& d : cell_out) in[d.to].push_back(&d);
    cells_of_polygon.resize(polygons.size());
    for (std::uint32_t c = 0; c < part.cells.size(); ++c)
      for (const auto p : part.cell_polygons[c]) cells_of_polygon[p].push_back(c);
  }
};

class Flow {
 public:
  Flow(const Partition& part, const FlowGraph& graph, const std::vector<VisPolygon>& polys,
       const FlowOptions& options)
      : part_(part), graph_(graph), polys_(polys), budget_(options.budget), cull_(options.cull_back_faces) {}

  void run(std::uint32_t cell, std::vector<std::uint32_t>& cells, std::vector<std::uint32_t>& visible,
           std::uint64_t& steps, std::uint64_t& occluded, bool& fell_back, bool& cell_fell_back) {
    occluded_ = 0;
    seen_cell_.assign(part_.cells.size(), 0);
    seen_poly_.assign(polys_.size(), 0);
    done_.assign((part_.cells.size() + 63) / 64, 0);
    unseen_in_cell_.resize(part_.cells.size());
    for (std::uint32_t c = 0; c < part_.cells.size(); ++c)
      unseen_in_cell_[c] = static_cast<std::uint32_t>(part_.cell_polygons[c].size());
    on_stack_.assign(part_.cells.size(), 0);
    steps_ = 0;
    mark_all(cell);
    on_stack_[cell] = 1;
    for (const auto& d : graph_.out[cell]) {
      if (all_done(d.might)) continue;
      source_plane_ = d.plane;
      recurse(d.to, *d.winding, nullptr, nullptr, d.might);
      if (steps_ > budget_) break;
    }
    fell_back = steps_ > budget_;
    if (fell_back) {
      // Too many sequences to test every item along each: find the cells by a flow that stops where no new
      // cell can be reached, then test the items of each reached cell by portal pairs.
      steps += steps_;
      steps_ = 0;
      reached_.assign(done_.size(), 0);
      for (std::uint32_t c = 0; c < seen_cell_.size(); ++c)
        if (seen_cell_[c]) set_bit(reached_, c);
      const std::uint64_t cell_budget = budget_ * kCellFlowBudgetFactor;
      for (const auto& d : graph_.out[cell]) {
        if (subset(d.might, reached_)) continue;
        source_plane_ = d.plane;
        recurse_cells(d.to, *d.winding, nullptr, d.might, cell_budget);
        if (steps_ > cell_budget) break;
      }
      cell_fell_back = steps_ > cell_budget;
      if (cell_fell_back) might_see_all(cell);
      items_by_pairs(cell);
    }
    steps += steps_;
    occluded += occluded_;
    for (std::uint32_t c = 0; c < seen_cell_.size(); ++c)
      if (seen_cell_[c]) cells.push_back(c);
    for (std::uint32_t p = 0; p < seen_poly_.size(); ++p)
      if (seen_poly_[p]) visible.push_back(p);
  }

 private:
  bool all_done(const Bits& cells) const {
    for (std::size_t w = 0; w < cells.size(); ++w)
      if (cells[w] & ~done_[w]) return false;
    return true;
  }
  // A cell is done when it has been reached and every polygon in it is in the PVS.
  void see_cell(std::uint32_t c) {
    if (seen_cell_[c]) return;
    seen_cell_[c] = 1;
    if (unseen_in_cell_[c] == 0) set_bit(done_, c);
  }
  void see_polygon(std::uint32_t p) {
    if (seen_poly_[p]) return;
    seen_poly_[p] = 1;
    for (const auto c : graph_.cells_of_polygon[p])
      if (--unseen_in_cell_[c] == 0 && seen_cell_[c]) set_bit(done_, c);
  }
  void mark_all(std::uint32_t c) {
    see_cell(c);
    for (const auto p : part_.cell_polygons[c]) see_polygon(p);
  }

  // Past the cell flow's budget too: every cell that a sight line through one of the cell's portals might
  // reach. Conservative (each might-see set holds every cell such a sight line can reach), and tighter than
  // a flood through every portal.
  void might_see_all(std::uint32_t cell) {
    for (const auto& d : graph_.out[cell])
      for (std::uint32_t c = 0; c < part_.cells.size(); ++c)
        if (bit(d.might, c)) {
          see_cell(c);
          set_bit(reached_, c);
        }
  }

  static bool subset(const Bits& a, const Bits& b) {
    for (std::size_t w = 0; w < a.size(); ++w)
      if (a[w] & ~b[w]) return false;
    return true;
  }

  // Quake vis's flow at the level of cells: a sequence goes on only while some cell every portal passed
  // might see is not reached yet. Unexplored sequences reach only cells already reached, so the set is the
  // one an exhaustive flow finds, at a small part of the cost.
  void recurse_cells(std::uint32_t cell, const Winding& source, const Winding* pass, const Bits& might,
                     std::uint64_t budget) {
    if (++steps_ > budget) return;
    see_cell(cell);
    set_bit(reached_, cell);
    std::vector<Plane> seps;
    if (pass) {
      separating_planes(source, *pass, false, seps);
      separating_planes(*pass, source, true, seps);
    }
    const Winding& light = pass ? *pass : source;
    on_stack_[cell] = 1;
    Bits next_might(might.size());
    for (const auto& d : graph_.out[cell]) {
      if (on_stack_[d.to]) continue;
      for (std::size_t w = 0; w < might.size(); ++w) next_might[w] = might[w] & d.might[w];
      if (subset(next_might, reached_)) continue;
      Winding target, narrowed;
      if (!step_through(d, cell, source, pass, seps, light, target, narrowed)) continue;
      recurse_cells(d.to, narrowed, &target, next_might, budget);
      if (steps_ > budget) break;
    }
    on_stack_[cell] = 0;
  }

  // Is item p seen through the region `planes` bound (a detail cluster by its box), and not hidden from
  // `light` by an occluder of `cell`?
  bool seen_through(std::uint32_t p, const std::vector<Plane>& planes, std::uint32_t cell,
                    const Winding& light) {
    const VisPolygon& item = polys_[p];
    return (item.detail ? box_meets_region(item.box, planes) : survives(item.hull, planes)) &&
           !occluded(outline(p), cell, light);
  }

  // The items of each reached cell, tested by portal pairs. A sight line from `cell` to a point of another
  // cell Z leaves through one of the cell's portals d and enters Z last through a portal e from a reached
  // cell, so the point lies where lines through both d and e go on past e: in front of the planes
  // separating d and e, of e and of d. Every such pair is tried (not only the sequences the cell flow
  // followed), which keeps the set conservative while the flow prunes; it is looser than testing along each
  // sequence, since the portals between d and e narrow nothing.
  void items_by_pairs(std::uint32_t cell) {
    std::vector<Plane> planes;
    for (std::uint32_t z = 0; z < part_.cells.size(); ++z) {
      if (!bit(reached_, z) || z == cell || unseen_in_cell_[z] == 0) continue;
      for (const Directed* e : graph_.in[z]) {
        if (e->from != cell && !bit(reached_, e->from)) continue;
        if (e->from == cell) {
          // e is one of the cell's own portals: everything past it may be seen.
          planes.assign(1, e->plane);
          for (const auto p : part_.cell_polygons[z])
            if (!seen_poly_[p] && seen_through(p, planes, z, *e->winding)) see_polygon(p);
          continue;
        }
        for (const auto& d : graph_.out[cell]) {
          if (!bit(d.might, e->from) || !bit(d.might, z)) continue;
          const Winding source = clip_front(*d.winding, e->plane.flipped());
          if (winding_width(source) < kSliverWidth) continue;
          const Winding target = clip_front(*e->winding, d.plane);
          if (winding_width(target) < kSliverWidth) continue;
          planes.clear();
          separating_planes(source, target, false, planes);
          separating_planes(target, source, true, planes);
          planes.push_back(e->plane);
          planes.push_back(d.plane);
          for (const auto p : part_.cell_polygons[z])
            if (!seen_poly_[p] && seen_through(p, planes, z, target)) see_polygon(p);
          if (unseen_in_cell_[z] == 0) break;
        }
        if (unseen_in_cell_[z] == 0) break;
      }
    }
  }

  static bool survives(Winding w, const std::vector<Plane>& planes) {
    // Most polygons fail wholly behind one plane: find that without clipping (no allocation), then clip.
    for (const auto& p : planes) {
      bool any = false;
      for (const auto& v : w) any = any || p.distance(v) >= -kPlaneEpsilon;
      if (!any) return false;
    }
    return !clip_front_all(std::move(w), planes).empty();
  }

  // What an occluder must hide of item p: its hull, or a detail cluster's box corners (the occluder test
  // projects points from the light, and a convex set's projection is the hull of its corners' ones).
  const Winding& outline(std::uint32_t p) const {
    return polys_[p].detail ? graph_.corners[p] : polys_[p].hull;
  }

  // Is `w` (in `cell` or on its boundary) wholly hidden behind one of the cell's occluders from `light`,
  // a portal every sight line into the cell crosses?
  bool occluded(const Winding& w, std::uint32_t cell, const Winding& light) {
    if (graph_.occluders.empty()) return false;
    for (const auto& o : graph_.occluders[cell])
      if (hidden_by(w, light, o, cull_)) {
        ++occluded_;
        return true;
      }
    return false;
  }

  // One step of a sequence out of `cell` through `d`, seen from `source` through `pass` (null: the first
  // portal), whose separating planes are `seps`: `target` is d clipped to what the source sees through the
  // pass, `narrowed` the part of the source that sees the target. False where nothing passes: the source
  // is not behind d, either is a sliver, or an occluder of the cell hides the target from `light`.
  bool step_through(const Directed& d, std::uint32_t cell, const Winding& source, const Winding* pass,
                    const std::vector<Plane>& seps, const Winding& light, Winding& target,
                    Winding& narrowed) {
    // The source must lie behind the next portal to see through it.
    narrowed = clip_front(source, d.plane.flipped());
    if (narrowed.empty()) return false;
    target = clip_front_all(clip_front(*d.winding, source_plane_), seps);
    if (winding_width(target) < kSliverWidth || occluded(target, cell, light)) return false;
    // Only part of the source sees the target through the pass: clip it by the planes separating the
    // target and the pass, both ways (as Quake's vis clips its source), so that every portal beyond is
    // clipped by the planes of a narrower source.
    if (pass) {
      std::vector<Plane> back;
      separating_planes(target, *pass, false, back);
      separating_planes(*pass, target, true, back);
      narrowed = clip_front_all(std::move(narrowed), back);
    }
    return winding_width(narrowed) >= kSliverWidth;
  }

  // Entering `cell`, seen from `source` (part of the first portal) through `pass` (the last portal passed,
  // clipped), or directly through the first portal when pass is null.
  // `might`: the cells every portal passed so far might see.
  void recurse(std::uint32_t cell, const Winding& source, const Winding* pass, const Plane* pass_plane,
               const Bits& might) {
    if (++steps_ > budget_) return;
    std::vector<Plane> seps;
    const Winding& light = pass ? *pass : source;  // every sight line into the cell crosses it
    see_cell(cell);
    if (!pass) {
      // The cell just beyond the first portal: anything in front of the portal may be seen, unless an
      // occluder hides it.
      const std::vector<Plane> front{source_plane_};
      for (const auto p : part_.cell_polygons[cell])
        if (!seen_poly_[p] && seen_through(p, front, cell, light)) see_polygon(p);
    } else {
      separating_planes(source, *pass, false, seps);
      separating_planes(*pass, source, true, seps);
      std::vector<Plane> test = seps;
      test.push_back(*pass_plane);
      test.push_back(source_plane_);
      for (const auto p : part_.cell_polygons[cell])
        if (!seen_poly_[p] && seen_through(p, test, cell, light)) see_polygon(p);
    }
    on_stack_[cell] = 1;
    Bits next_might(might.size());
    for (const auto& d : graph_.out[cell]) {
      if (on_stack_[d.to]) continue;
      for (std::size_t w = 0; w < might.size(); ++w) next_might[w] = might[w] & d.might[w];
      if (all_done(next_might)) continue;
      Winding target, narrowed;
      if (!step_through(d, cell, source, pass, seps, light, target, narrowed)) continue;
      recurse(d.to, narrowed, &target, &d.plane, next_might);
      if (steps_ > budget_) break;
    }
    on_stack_[cell] = 0;
  }

  const Partition& part_;
  const FlowGraph& graph_;
  const std::vector<VisPolygon>& polys_;
  std::uint64_t budget_;
  bool cull_;
  std::uint64_t occluded_ = 0;
  std::vector<char> seen_cell_, seen_poly_, on_stack_;
  std::vector<std::uint32_t> unseen_in_cell_;
  Bits done_;
  Bits reached_;  // cells the cell-level flow has reached
  Plane source_plane_;
  std::uint64_t steps_ = 0;
};

}  // namespace

FlowPvs portal_flow_pvs(const Partition& partition, const PortalGraph& graph,
                        const std::vector<VisPolygon>& polygons, const FlowOptions& options) {
  FlowPvs r;
  const std::size_t n = partition.cells.size();
  r.cells.resize(n);
  r.polygons.resize(n);
  std::vector<std::uint64_t> steps(n, 0), occluded(n, 0);
  std::vector<char> fell(n, 0), cell_fell(n, 0);
  const FlowGraph flow_graph(partition, graph, polygons, options.occluders);
  Progress progress("cells: visibility flow", n, "cells");
  parallel_for(n, options.threads, [&](std::size_t c) {
    progress.advance();
    if (!options.sources.empty() && !options.sources[c]) return;
    Flow flow(partition, flow_graph, polygons, options);
    bool fb = false, cell_fb = false;
    flow.run(static_cast<std::uint32_t>(c), r.cells[c], r.polygons[c], steps[c], occluded[c], fb, cell_fb);
    fell[c] = fb;
    cell_fell[c] = cell_fb;
  });
  for (std::size_t c = 0; c < n; ++c) {
    r.steps += steps[c];
    r.occluded += occluded[c];
    r.fallbacks += fell[c];
    r.cell_fallbacks += cell_fell[c];
  }
  return r;
}

}  // namespace walk::compiler
