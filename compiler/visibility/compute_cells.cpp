#include "compiler/visibility/compute_cells.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <iterator>

#include "compiler/visibility/draw_order.hpp"
#include "compiler/visibility/parallel_for.hpp"
#include "compiler/visibility/pvs_flow.hpp"
#include "compiler/visibility/pvs_sampled.hpp"

namespace walk::compiler {
namespace {

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::vector<std::uint32_t> united(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> u;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(u));
  return u;
}

// Leaves out of each cell's PVS the polygons proven hidden from the whole cell; those a sample saw are
// visible and not tried.
void prove_hidden(VisibilityResult& r, const std::vector<std::vector<std::uint32_t>>& sampled,
                  const RayCaster& caster, const VisibilityConfig& config) {
  const HiddenProver prover(r.polygons, caster, config.cull_back_faces);
  const ProofOptions options{config.proof_pairs, ProofOptions{}.max_depth, config.cull_back_faces};
  std::vector<ProofStats> stats(r.pvs.size());
  parallel_for(r.pvs.size(), config.threads, [&](std::size_t c) {
    const Box& box = r.partition.cells[c];
    std::vector<HiddenProver::Exit> exits;
    for (const auto id : r.graph.cell_portals[c]) {
      const Portal& portal = r.graph.portals[id];
      if (!portal.open_from(static_cast<std::uint32_t>(c)) || portal.hull.size() < 3) continue;
      exits.push_back({portal.hull, portal.out_of(static_cast<std::uint32_t>(c))});
    }
    std::erase_if(r.pvs[c], [&](std::uint32_t p) {
      if (std::binary_search(sampled[c].begin(), sampled[c].end(), p)) return false;
      return prover.prove(box, exits, p, options, &stats[c]) == Verdict::Hidden;
    });
  });
  for (const auto& s : stats) r.proofs.add(s);
}

}  // namespace

std::string VisibilityResult::summary() const {
  std::size_t total = 0, worst = 0;
  for (const auto& p : pvs) {
    total += p.size();
    worst = std::max(worst, p.size());
  }
  const double avg = pvs.empty() ? 0.0 : double(total) / double(pvs.size());
  return fmt::format(
      "{} cells (depth {}, {} candidate planes), {} portals, {} leaks, PVS avg {:.0f} worst {} of {} "
      "polygons; "
      "flow {} steps, {} fallbacks, {} occluded; {} sample rays; {} back faces dropped; "
      "proofs {} tried, {} hidden, {} seen, {} undecided in {} pairs; "
      "partition {:.2f} s portals {:.2f} s pvs {:.2f} s (proofs {:.2f} s)",
      partition.cells.size(), partition.depth, partition.candidates, graph.portals.size(), graph.leaks.size(),
      avg, worst, polygons.size(), flow_steps, flow_fallbacks, flow_occluded, sample_rays, back_faces_dropped,
      proofs.tried, proofs.hidden, proofs.visible, proofs.undecided, proofs.pairs, seconds_partition,
      seconds_portals, seconds_pvs, seconds_proofs);
}

VisibilityResult compute_visibility(std::span<const model::VertexRecord> vertices,
                                    std::span<const std::uint32_t> indices,
                                    std::span<const model::PolygonRecord> polygons,
                                    const VisibilityConfig& config) {
  VisibilityResult r;
  auto t = std::chrono::steady_clock::now();
  r.polygons = vis_polygons(vertices, indices, polygons);
  r.partition = build_partition(r.polygons, config);
  r.seconds_partition = since(t);
  t = std::chrono::steady_clock::now();
  r.graph = find_portals(r.partition, r.polygons, config.cull_back_faces);
  r.seconds_portals = since(t);
  for (const auto& leak : r.graph.leaks)
    spdlog::debug("leak: {:.3f} m2 open to the outside at local ({:.3f}, {:.3f}, {:.3f}) in cell {}",
                  leak.area, leak.where.x, leak.where.y, leak.where.z, leak.cell);
  t = std::chrono::steady_clock::now();
  const std::size_t n = r.partition.cells.size();
  std::vector<std::vector<std::uint32_t>> sampled, flow_polys;
  std::unique_ptr<RayCaster> caster;
  if (config.method == PvsMethod::Sampled || config.method == PvsMethod::Combined) {
    std::vector<Triangle> triangles;
    for (std::uint32_t p = 0; p < r.polygons.size(); ++p)
      for (const auto& tri : r.polygons[p].triangles) triangles.push_back({tri[0], tri[1], tri[2], p});
    caster = make_ray_caster(config.ray_caster, triangles);
    sampled = sampled_pvs(
        r.partition, r.graph, r.polygons, *caster,
        {config.sample_points, config.rays_per_point, config.seed, config.threads, config.cull_back_faces},
        &r.sample_rays);
  }
  if (config.method != PvsMethod::Sampled) {
    FlowPvs flow =
        portal_flow_pvs(r.partition, r.graph, r.polygons,
                        {config.flow_budget, config.threads, config.occluders, config.cull_back_faces});
    r.flow_steps = flow.steps;
    r.flow_occluded = flow.occluded;
    r.flow_fallbacks = flow.fallbacks;
    r.flow_cells = std::move(flow.cells);
    flow_polys = std::move(flow.polygons);
  }
  r.pvs.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    switch (config.method) {
      case PvsMethod::Sampled:
        r.pvs[c] = std::move(sampled[c]);
        break;
      case PvsMethod::Conservative:
        for (const auto d : r.flow_cells[c]) r.pvs[c] = united(r.pvs[c], r.partition.cell_polygons[d]);
        break;
      case PvsMethod::Combined:
        r.pvs[c] = united(flow_polys[c], sampled[c]);
        break;
    }
  }
  if (config.cull_back_faces) {
    // The renderer culls back faces: an opaque polygon turned away from the whole cell is never drawn there.
    for (std::size_t c = 0; c < n; ++c) {
      const Box& box = r.partition.cells[c];
      std::erase_if(r.pvs[c], [&](std::uint32_t p) {
        const bool away = r.polygons[p].opaque && faces_away_from(r.polygons[p], box);
        r.back_faces_dropped += away ? 1 : 0;
        return away;
      });
    }
  }
  // After the back-face pass: a polygon turned away from the whole cell needs no proof.
  if (config.method == PvsMethod::Combined && config.proof_pairs > 0 && n > 1) {
    const auto tp = std::chrono::steady_clock::now();
    prove_hidden(r, sampled, *caster, config);
    r.seconds_proofs = since(tp);
  }
  r.seconds_pvs = since(t);
  return r;
}

CellsStageCounts compute_cells(model::BundleContents& out, const VisibilityConfig& config) {
  const VisibilityResult r = compute_visibility(out.vertices, out.indices, out.polygons, config);
  out.cells.clear();
  out.nodes = r.partition.nodes;
  out.pvs.clear();
  for (std::size_t c = 0; c < r.partition.cells.size(); ++c) {
    model::CellRecord rec{};
    for (int a = 0; a < 3; ++a) {
      rec.bounds_min[a] = static_cast<float>(r.partition.cells[c].min[a]);
      rec.bounds_max[a] = static_cast<float>(r.partition.cells[c].max[a]);
    }
    rec.pvs_first = static_cast<std::uint32_t>(out.pvs.size());
    rec.pvs_count = static_cast<std::uint32_t>(r.pvs[c].size());
    out.pvs.insert(out.pvs.end(), r.pvs[c].begin(), r.pvs[c].end());
    out.cells.push_back(rec);
  }
  // The largest few openings are named; the count is in the stage detail.
  auto leaks = r.graph.leaks;
  std::sort(leaks.begin(), leaks.end(), [](const Leak& a, const Leak& b) { return a.area > b.area; });
  for (std::size_t i = 0; i < std::min<std::size_t>(leaks.size(), 3); ++i)
    spdlog::warn("visibility: leak to the outside, {:.4f} m2 at world ({:.3f}, {:.3f}, {:.3f})",
                 leaks[i].area, leaks[i].where.x + out.meta.origin[0], leaks[i].where.y + out.meta.origin[1],
                 leaks[i].where.z + out.meta.origin[2]);
  const DrawOrderCounts order = order_for_cells(out);
  return {out.polygons.size(), out.cells.size(),
          std::string(pvs_method_name(config.method)) + ": " + r.summary() +
              fmt::format("; draw ranges {} -> {} over all cells", order.ranges_before, order.ranges_after)};
}

}  // namespace walk::compiler
