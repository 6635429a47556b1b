#include "compiler/visibility/pvs_flow.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <bit>
#include <iterator>
#include <utility>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "compiler/visibility/vis_items.hpp"

namespace walk::compiler {
namespace {

// A flow past its budget gets this many times the budget again for the cell-level flow, whose steps test
// no items and prune far more. Once: on the generated M building the 87 portals whose cell flows ran past
// ten times the budget spent 94 of the flow's 203 thread-seconds to end with all they might see anyway;
// at once the budget, the flow took 58 s instead of 107 and the PVS grew from 809 to 823 items on average.
constexpr std::uint64_t kCellFlowBudgetFactor = 1;
// Portals are flowed in waves of this many, each wave bounded by the flows of the waves before it: fixed,
// not by thread count, so the PVS is the same whatever the threads.
constexpr std::size_t kFlowWave = 32;
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
  std::uint32_t index = 0;  // in FlowGraph::directed
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
  std::vector<const Directed*> directed;         // every directed portal, by Directed::index

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
    for (auto& cell_out : out)
      for (auto& d : cell_out) {
        in[d.to].push_back(&d);
        d.index = static_cast<std::uint32_t>(directed.size());
        directed.push_back(&d);
      }
    cells_of_polygon.resize(polygons.size());
    for (std::uint32_t c = 0; c < part.cells.size(); ++c)
      for (const auto p : part.cell_polygons[c]) cells_of_polygon[p].push_back(c);
  }
};

// What sight lines through one directed portal reach (Quake vis's portalvis): the cells and the items
// beyond it, out of the cell it leads from.
struct PortalVis {
  Bits cells;                        // one bit per cell reached
  std::vector<std::uint32_t> items;  // items seen (sorted)
  std::uint64_t steps = 0, occluded = 0;
  bool fell_back = false;       // the flow ran past its budget: cells by a cell flow, items by portal pairs
  bool cell_fell_back = false;  // ... whose cell flow did too: all the portal might see
};

class Flow {
 public:
  // `complete`: per directed portal, whether `vis` holds its finished flow (read only while this runs).
  Flow(const Partition& part, const FlowGraph& graph, const std::vector<VisPolygon>& polys,
       const FlowOptions& options, const std::vector<PortalVis>& vis, const std::vector<char>& complete)
      : part_(part),
        graph_(graph),
        polys_(polys),
        vis_(vis),
        complete_(complete),
        budget_(options.budget),
        cull_(options.cull_back_faces) {}

  // The flow through `source` alone: every sequence that starts with it.
  PortalVis run(const Directed& source) {
    occluded_ = 0;
    seen_cell_.assign(part_.cells.size(), 0);
    seen_poly_.assign(polys_.size(), 0);
    done_.assign((part_.cells.size() + 63) / 64, 0);
    unseen_in_cell_.resize(part_.cells.size());
    for (std::uint32_t c = 0; c < part_.cells.size(); ++c)
      unseen_in_cell_[c] = static_cast<std::uint32_t>(part_.cell_polygons[c].size());
    on_stack_.assign(part_.cells.size(), 0);
    steps_ = 0;
    on_stack_[source.from] = 1;  // cells are convex: a sight line leaving one never comes back
    PortalVis out;
    source_plane_ = source.plane;
    recurse(source.to, *source.winding, nullptr, nullptr, source.might);
    out.fell_back = steps_ > budget_;
    if (out.fell_back) {
      // Too many sequences to test every item along each: find the cells by a flow that stops where no new
      // cell can be reached, then test the items of each reached cell by portal pairs.
      out.steps += steps_;
      steps_ = 0;
      reached_.assign(done_.size(), 0);
      for (std::uint32_t c = 0; c < seen_cell_.size(); ++c)
        if (seen_cell_[c]) set_bit(reached_, c);
      const std::uint64_t cell_budget = budget_ * kCellFlowBudgetFactor;
      recurse_cells(source.to, *source.winding, nullptr, source.might, cell_budget);
      out.cell_fell_back = steps_ > cell_budget;
      if (out.cell_fell_back) might_see_all(source);
      items_by_pairs(source);
    }
    out.steps += steps_;
    out.occluded = occluded_;
    out.cells.assign(done_.size(), 0);
    for (std::uint32_t c = 0; c < seen_cell_.size(); ++c)
      if (seen_cell_[c]) set_bit(out.cells, c);
    for (std::uint32_t p = 0; p < seen_poly_.size(); ++p)
      if (seen_poly_[p]) out.items.push_back(p);
    return out;
  }

 private:
  // The cells a sight line through d may reach: those its finished flow reached, else its might-see set
  // (Quake vis's trick: portals are flowed in order of fewest might-see cells, so the flows through the
  // narrow portals are done when the wide ones pass them, and bound them far more tightly).
  const Bits& bound_of(const Directed& d) const { return complete_[d.index] ? vis_[d.index].cells : d.might; }

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

  // Past the cell flow's budget too: every cell that a sight line through the portal might reach.
  // Conservative (the might-see set holds every cell such a sight line can reach), and tighter than a flood
  // through every portal.
  void might_see_all(const Directed& source) {
    for (std::uint32_t c = 0; c < part_.cells.size(); ++c)
      if (bit(source.might, c)) {
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
      const Bits& through = bound_of(d);
      for (std::size_t w = 0; w < might.size(); ++w) next_might[w] = might[w] & through[w];
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

  // The items of each reached cell, tested by portal pairs. A sight line through `d` to a point of another
  // cell Z enters Z last through a portal e from a reached cell, so the point lies where lines through both
  // d and e go on past e: in front of the planes separating d and e, of e and of d. Every such pair is
  // tried (not only the sequences the cell flow followed), which keeps the set conservative while the flow
  // prunes; it is looser than testing along each sequence, since the portals between d and e narrow
  // nothing.
  void items_by_pairs(const Directed& d) {
    std::vector<Plane> planes;
    for (std::uint32_t z = 0; z < part_.cells.size(); ++z) {
      if (!bit(reached_, z) || z == d.from || unseen_in_cell_[z] == 0) continue;
      for (const Directed* e : graph_.in[z]) {
        if (e == &d) {
          // Just past d: everything in front of it may be seen.
          planes.assign(1, e->plane);
          for (const auto p : part_.cell_polygons[z])
            if (!seen_poly_[p] && seen_through(p, planes, z, *e->winding)) see_polygon(p);
          continue;
        }
        // A sight line through d leaves d's cell for good (cells are convex).
        if (e->from == d.from || !bit(reached_, e->from)) continue;
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
      const Bits& through = bound_of(d);
      for (std::size_t w = 0; w < might.size(); ++w) next_might[w] = might[w] & through[w];
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
  const std::vector<PortalVis>& vis_;
  const std::vector<char>& complete_;
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
  const FlowGraph flow_graph(partition, graph, polygons, options.occluders);
  // The portals out of the cells flows start in, fewest might-see cells first.
  std::vector<const Directed*> order;
  for (const Directed* d : flow_graph.directed)
    if (options.sources.empty() || options.sources[d->from]) order.push_back(d);
  auto might_count = [](const Directed* d) {
    std::size_t k = 0;
    for (const auto w : d->might) k += std::size_t(std::popcount(w));
    return k;
  };
  std::vector<std::size_t> counts(flow_graph.directed.size());
  for (const Directed* d : order) counts[d->index] = might_count(d);
  std::stable_sort(order.begin(), order.end(),
                   [&](const Directed* a, const Directed* b) { return counts[a->index] < counts[b->index]; });
  std::vector<PortalVis> vis(flow_graph.directed.size());
  std::vector<char> complete(flow_graph.directed.size(), 0);
  Progress progress("cells: visibility flow", order.size(), "portals");
  for (std::size_t first = 0; first < order.size(); first += kFlowWave) {
    const std::size_t last = std::min(order.size(), first + kFlowWave);
    parallel_for(last - first, options.threads, [&](std::size_t k) {
      const Directed& d = *order[first + k];
      Flow flow(partition, flow_graph, polygons, options, vis, complete);
      vis[d.index] = flow.run(d);
      progress.advance();
    });
    for (std::size_t k = first; k < last; ++k) complete[order[k]->index] = 1;
  }
  // A cell sees itself and what its portals see.
  parallel_for(n, options.threads, [&](std::size_t c) {
    if (!options.sources.empty() && !options.sources[c]) return;
    Bits cells((n + 63) / 64, 0);
    set_bit(cells, static_cast<std::uint32_t>(c));
    std::vector<std::uint32_t> items = partition.cell_polygons[c];
    std::sort(items.begin(), items.end());
    for (const auto& d : flow_graph.out[c]) {
      const PortalVis& v = vis[d.index];
      for (std::size_t w = 0; w < cells.size(); ++w) cells[w] |= v.cells[w];
      std::vector<std::uint32_t> both;
      std::set_union(items.begin(), items.end(), v.items.begin(), v.items.end(), std::back_inserter(both));
      items = std::move(both);
    }
    for (std::uint32_t x = 0; x < n; ++x)
      if (bit(cells, x)) r.cells[c].push_back(x);
    r.polygons[c] = std::move(items);
  });
  for (const Directed* d : order) {
    const PortalVis& v = vis[d->index];
    r.steps += v.steps;
    r.occluded += v.occluded;
    r.fallbacks += v.fell_back;
    r.cell_fallbacks += v.cell_fell_back;
    if (v.fell_back)
      spdlog::debug("visibility: the flow through portal {} out of cell {} ran past {} steps{}", d->index,
                    d->from, options.budget,
                    v.cell_fell_back ? " (its cell flow too: all it might see)" : "");
  }
  return r;
}

}  // namespace walk::compiler
