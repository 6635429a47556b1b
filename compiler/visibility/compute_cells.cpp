#include "compiler/visibility/compute_cells.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>

#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "compiler/visibility/draw_order.hpp"
#include "compiler/visibility/inside_flood.hpp"
#include "compiler/visibility/open_regions.hpp"
#include "compiler/visibility/pvs_flow.hpp"
#include "compiler/visibility/pvs_sampled.hpp"
#include "compiler/visibility/vis_items.hpp"
#include "compiler/visibility/voxel_flood.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

// The float nearest below (above) `x`: a box stored in float must still hold what it held in double.
float round_down(double x) {
  const auto f = static_cast<float>(x);
  return double(f) <= x ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float round_up(double x) {
  const auto f = static_cast<float>(x);
  return double(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

// Pairs the proof may try per detail cluster (at most proof_pairs): a cluster proof is six box faces, and
// most that a few pairs leave undecided stay so. On the generated S building 32 pairs take the proofs
// from 11.7 s (256 pairs) to 3.6 s, and the PVS from 545 to 567 items on average (620 with no cluster
// proofs, 1.7 s).
constexpr int kClusterProofPairs = 32;

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::vector<std::uint32_t> united(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> u;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(u));
  return u;
}

// Leaves out of each cell's PVS (cells of `part`: the partition's, or its open regions) the polygons proven
// hidden from the whole cell; those a sample saw are visible and not tried.
void prove_hidden(VisibilityResult& r, std::vector<std::vector<std::uint32_t>>& pvs,
                  const std::vector<std::vector<std::uint32_t>>& sampled, const Partition& part,
                  const PortalGraph& graph, const RayCaster& caster, const VisibilityConfig& config) {
  const HiddenProver prover(r.polygons, caster, config.cull_back_faces);
  const ProofOptions options{config.proof_pairs, ProofOptions{}.max_depth, config.cull_back_faces};
  const int least_pairs = std::min(config.proof_pairs, kClusterProofPairs);
  auto to_try = [&](std::size_t c, std::uint32_t p) {
    return !std::binary_search(sampled[c].begin(), sampled[c].end(), p);
  };
  // Per cell, the mean triangles of the items its proofs try (0: none).
  std::vector<double> mean_triangles(pvs.size(), 0.0);
  for (std::size_t c = 0; c < pvs.size(); ++c) {
    double triangles = 0.0, items = 0.0;
    for (const auto p : pvs[c])
      if (to_try(c, p)) {
        triangles += double(r.polygons[p].drawn_triangles);
        items += 1.0;
      }
    if (items > 0.0) mean_triangles[c] = triangles / items;
  }
  // An item's allowance follows the triangles hiding it takes out of the cell's draw (proof_allowance): on M,
  // 88 % of the walls proven hidden took 32 pairs or fewer, while 128 k walls of 72 triangles each spent
  // 244 pairs each on average to stay undecided, 68 % of all the pairs.
  auto allowance = [&](std::size_t c, std::uint32_t p) {
    return proof_allowance(r.polygons[p].drawn_triangles, mean_triangles[c], r.polygons[p].detail,
                           config.proof_pairs, least_pairs);
  };
  // The whole proof's work before any of it: each item to try (in the PVS, seen by no sample) may take its
  // allowance of pairs. Above the model's budget every allowance shrinks in proportion, with a warning: an
  // item undecided when its pairs run out stays in the PVS, so the cap costs tightness, never a missed pixel,
  // and refusing here would throw away the cells work already done.
  double wanted = 0.0;
  for (std::size_t c = 0; c < pvs.size(); ++c)
    for (const auto p : pvs[c])
      if (to_try(c, p)) wanted += allowance(c, p);
  r.proof_pairs_wanted = wanted;
  spdlog::debug("visibility: proofs may try up to {:.3g} pairs (budget {:.3g})", wanted,
                config.proof_pair_budget);
  double scale = 1.0;
  auto scaled = [&](int pairs) { return std::max(1, static_cast<int>(pairs * scale)); };
  if (wanted > config.proof_pair_budget) {
    scale = config.proof_pair_budget / wanted;
    r.proof_pairs_capped = scaled(config.proof_pairs);
    spdlog::warn(
        "{}: [visibility] proof_pairs = {} would let the hidden-item proofs try up to {:.3g} pairs, above "
        "the budget of {:.3g}: each item gets at most {} pairs (clusters {}); items left undecided stay in "
        "the PVS. Lower proof_pairs to {} or less to choose yourself",
        config.source, config.proof_pairs, wanted, config.proof_pair_budget, r.proof_pairs_capped,
        scaled(least_pairs), r.proof_pairs_capped);
  }
  std::vector<ProofStats> stats(pvs.size());
  Progress progress("cells: hidden proofs", pvs.size(), "cells");
  parallel_for(pvs.size(), config.threads, [&](std::size_t c) {
    const Box& box = part.cells[c];
    std::vector<HiddenProver::Exit> exits;
    for (const auto id : graph.cell_portals[c]) {
      const Portal& portal = graph.portals[id];
      if (!portal.open_from(static_cast<std::uint32_t>(c)) || portal.hull.size() < 3) continue;
      exits.push_back({portal.hull, portal.out_of(static_cast<std::uint32_t>(c))});
    }
    std::erase_if(pvs[c], [&](std::uint32_t p) {
      if (!to_try(c, p)) return false;
      ProofOptions o = options;
      o.max_pairs = scaled(allowance(c, p));
      return prover.prove(box, exits, p, o, &stats[c]) == Verdict::Hidden;
    });
    progress.advance();
  });
  for (const auto& s : stats) r.proofs.add(s);
}

}  // namespace

std::string VisibilityResult::summary() const {
  std::size_t total = 0, worst = 0;
  std::size_t walked = 0;
  for (std::size_t c = 0; c < pvs.size(); ++c) {
    if (!inside[c]) continue;
    const auto& p = pvs[c];
    ++walked;
    total += p.size();
    worst = std::max(worst, p.size());
  }
  const double avg = walked == 0 ? 0.0 : double(total) / double(walked);
  return fmt::format(
      "{} structure polygons, {} detail polygons in {} clusters; "
      "{} cells ({} outside; depth {}, {} candidate planes){}, {} portals, {} leaks{}, PVS avg {:.0f} "
      "worst {} of {} items; "
      "flow {} steps, {} portals past budget ({} to might-see), {} occluded; {} sample rays; {} back faces "
      "dropped; "
      "proofs {} tried, {} hidden, {} seen, {} undecided in {} pairs{}; "
      "partition {:.2f} s portals {:.2f} s pvs {:.2f} s (proofs {:.2f} s)",
      structure_items, detail_polygons, polygons.size() - structure_items, partition.cells.size(),
      std::count(inside.begin(), inside.end(), 0), partition.depth, partition.candidates,
      regions == 0
          ? std::string()
          : fmt::format(
                " in {} open regions ({:.1f} M voxels, {:.0f} % solid; {} portals inside solids; {} items "
                "facing the void)",
                regions, double(region_voxels) * 1e-6,
                100.0 * double(region_solid_voxels) / double(std::max<std::uint64_t>(1, region_voxels)),
                region_portals_dropped, void_facing.size()),
      graph.portals.size(), leaks.size(),
      leaks_unconfirmed == 0
          ? std::string()
          : fmt::format(" ({} more openings the cell flood reached that the voxel flood did not)",
                        leaks_unconfirmed),
      avg, worst, polygons.size(), flow_steps, flow_fallbacks, flow_cell_fallbacks, flow_occluded,
      sample_rays, back_faces_dropped, proofs.tried, proofs.hidden, proofs.visible, proofs.undecided,
      proofs.pairs,
      proof_pairs_capped > 0 ? fmt::format(" (capped at {} an item)", proof_pairs_capped) : std::string(),
      seconds_partition, seconds_portals, seconds_pvs, seconds_proofs);
}

std::vector<std::uint32_t> VisibilityResult::polygons_of(std::span<const std::uint32_t> items) const {
  std::vector<std::uint32_t> out;
  for (const auto item : items) out.insert(out.end(), item_polygons[item].begin(), item_polygons[item].end());
  std::sort(out.begin(), out.end());
  return out;
}

VisibilityResult compute_visibility(std::span<const model::VertexRecord> vertices,
                                    std::span<const std::uint32_t> indices,
                                    std::span<const model::PolygonRecord> polygons,
                                    const VisibilityConfig& config, std::span<const std::string> group_names,
                                    std::span<const model::PolygonRecord> drawn_records,
                                    std::span<const std::uint32_t> drawn_indices) {
  VisibilityResult r;
  auto t = std::chrono::steady_clock::now();
  {
    std::vector<VisPolygon> drawn = vis_polygons(vertices, indices, polygons);
    if (drawn_records.size() == drawn.size())
      for (std::size_t p = 0; p < drawn.size(); ++p)
        drawn[p].drawn_triangles = drawn_records[p].index_count / 3;
    const std::vector<char> structure = structure_polygons(drawn, polygons, group_names, config);
    VisItems items = make_vis_items(std::move(drawn), polygons, structure);
    r.polygons = std::move(items.items);
    r.item_polygons = std::move(items.polygons);
    r.structure_items = items.structure;
    r.detail_polygons = items.detail_polygons;
  }
  r.partition = build_partition(r.polygons, config);
  r.seconds_partition = since(t);
  t = std::chrono::steady_clock::now();
  r.graph = find_portals(r.partition, r.polygons, config.cull_back_faces, config.solids);
  // With solids, everything from the flood on runs over the cells' open regions ("view cells"), folded
  // back into cells at the end; without, the view cells are the cells.
  std::optional<OpenRegions> regions;
  if (!config.solids.empty()) {
    regions = open_regions(r.partition, r.graph, r.polygons, config.solids, config.threads);
    r.regions = regions->cell_of.size();
    r.region_voxels = regions->voxels;
    r.region_solid_voxels = regions->solid_voxels;
    r.region_portals_dropped = regions->portals_dropped;
  }
  const Partition& view = regions ? regions->partition : r.partition;
  const PortalGraph& view_graph = regions ? regions->graph : r.graph;
  r.seconds_portals = since(t);
  std::vector<char> view_inside;
  {
    std::function<std::uint32_t(const model::Vec3&)> locate_seed;
    if (regions)
      locate_seed = [&](const model::Vec3& p) { return regions->locate(locate(r.partition.nodes, p), p); };
    // Cells are boxes: past a slanted roof or wall they reach the boundary, so an opening the flood reaches
    // is a leak only where a voxel flood from the same seeds, stopped by the surfaces themselves, reaches
    // the outside beyond it too (made on the first such opening). Solids have their own open regions.
    std::optional<VoxelFlood> voxels;
    std::function<bool(const Leak&)> confirm;
    if (!regions)
      confirm = [&](const Leak& leak) {
        if (!voxels) voxels = flood_voxels(r.polygons, r.structure_items, view.bounds, config.seeds);
        Box face = view.cells[leak.cell];
        face.min[leak.axis] = face.max[leak.axis] =
            leak.max_side ? view.bounds.max[leak.axis] : view.bounds.min[leak.axis];
        const bool reached = voxels->reaches_beyond(face, leak.axis, leak.max_side);
        if (!reached)
          spdlog::debug(
              "visibility: opening of {:.4f} m2 at local ({:.3f}, {:.3f}, {:.3f}) not a leak: the voxel "
              "flood does not reach past it",
              leak.area, leak.where.x, leak.where.y, leak.where.z);
        return reached;
      };
    InsideFlood flood =
        flood_inside(view, view_graph, config.seeds, locate_seed, regions.has_value(), confirm);
    r.leaks_unconfirmed = flood.unconfirmed;
    view_inside = std::move(flood.inside);
    r.seeded = flood.seeds > 0;
    if (regions && r.seeded)
      r.void_facing = void_facing_items(*regions, r.partition, r.polygons, view_inside);
    if (r.seeded) {
      r.leaks = std::move(flood.leaks);
    } else {
      for (const auto& leak : view_graph.leaks) r.leaks.push_back({{leak.where}, leak.area});
      std::sort(r.leaks.begin(), r.leaks.end(),
                [](const LeakPath& a, const LeakPath& b) { return a.area > b.area; });
    }
  }
  t = std::chrono::steady_clock::now();
  const std::size_t n = r.partition.cells.size();
  const std::size_t nv = view.cells.size();
  const bool some_outside = std::find(view_inside.begin(), view_inside.end(), 0) != view_inside.end();
  std::vector<std::vector<std::uint32_t>> sampled, flow_polys, flow_cells;
  std::unique_ptr<RayCaster> caster;
  if (config.method == PvsMethod::Sampled || config.method == PvsMethod::Combined) {
    check_sample_budget(config, std::size_t(std::count(view_inside.begin(), view_inside.end(), 1)));
    // Detail hides nothing, so the caster holds each detail cluster's box, not its triangles: a sight line
    // that meets the box sees the cluster (more than its triangles would: conservative), and the caster is
    // the shell and twelve triangles a cluster (the conference room's 507,475 triangles made its polygon
    // BSP most of the cells stage).
    // Structure goes in as the display's triangles where they are given: the axial caster's in-plane grids
    // fit the lighting grid's small triangles better than whole-polygon slivers (M's proofs 52.5 -> 45.2 s).
    std::vector<Triangle> triangles;
    const bool diced = drawn_records.size() == polygons.size() && !drawn_indices.empty();
    auto position = [&](std::uint32_t i) {
      const auto& v = vertices[drawn_indices[i]].position;
      return model::Vec3(v[0], v[1], v[2]);
    };
    for (std::uint32_t p = 0; p < r.polygons.size(); ++p) {
      if (r.polygons[p].detail) {
        for (const auto& tri : box_shell(r.polygons[p].box)) triangles.push_back({tri[0], tri[1], tri[2], p});
      } else if (diced) {
        const auto& rec = drawn_records[r.item_polygons[p].front()];
        for (std::uint32_t i = rec.first_index; i + 2 < rec.first_index + rec.index_count; i += 3)
          triangles.push_back({position(i), position(i + 1), position(i + 2), p});
      } else {
        for (const auto& tri : r.polygons[p].triangles) triangles.push_back({tri[0], tri[1], tri[2], p});
      }
    }
    caster = make_ray_caster(config.ray_caster, triangles);
    SampledPvsOptions options{config.sample_points,   config.rays_per_point, config.seed, config.threads,
                              config.cull_back_faces, view_inside,           {}};
    if (regions)
      options.usable = [&](std::size_t region, const model::Vec3& p) {
        return regions->holds(static_cast<std::uint32_t>(region), p);
      };
    sampled = sampled_pvs(view, view_graph, r.polygons, *caster, options, &r.sample_rays);
  }
  if (config.method != PvsMethod::Sampled) {
    FlowOptions options{config.flow_budget, config.threads, config.occluders, config.cull_back_faces, {}};
    // Flows start only in the walk's cells, but pass through every cell: the cells off the walk (the
    // outside, a wall's hollow core, a window's reveal) are convex like the rest, so a sight line out of
    // a window meets another window only along a line that really passes between them.
    if (some_outside) options.sources.assign(view_inside.begin(), view_inside.end());
    FlowPvs flow = portal_flow_pvs(view, view_graph, r.polygons, options);
    flow_cells = std::move(flow.cells);
    flow_polys = std::move(flow.polygons);
    r.flow_steps = flow.steps;
    r.flow_occluded = flow.occluded;
    r.flow_fallbacks = flow.fallbacks;
    r.flow_cell_fallbacks = flow.cell_fallbacks;
  }
  std::vector<std::vector<std::uint32_t>> pvs(nv);
  for (std::size_t c = 0; c < nv; ++c) {
    if (!view_inside[c]) continue;  // off the walk: the renderer draws everything there
    switch (config.method) {
      case PvsMethod::Sampled:
        pvs[c] = std::move(sampled[c]);
        break;
      case PvsMethod::Conservative:
        for (const auto d : flow_cells[c]) pvs[c] = united(pvs[c], view.cell_polygons[d]);
        break;
      case PvsMethod::Combined:
        pvs[c] = united(flow_polys[c], sampled[c]);
        break;
    }
  }
  if (config.cull_back_faces) {
    // The renderer culls back faces: an opaque polygon turned away from the whole cell is never drawn there.
    for (std::size_t c = 0; c < nv; ++c) {
      const Box& box = view.cells[c];
      std::erase_if(pvs[c], [&](std::uint32_t p) {
        const bool away = r.polygons[p].opaque && faces_away_from(r.polygons[p], box);
        r.back_faces_dropped += away ? 1 : 0;
        return away;
      });
    }
  }
  // After the back-face pass: a polygon turned away from the whole cell needs no proof.
  if (config.method == PvsMethod::Combined && config.proof_pairs > 0 && nv > 1) {
    const auto tp = std::chrono::steady_clock::now();
    prove_hidden(r, pvs, sampled, view, view_graph, *caster, config);
    r.seconds_proofs = since(tp);
  }
  // Back to cells: a cell sees what any of its inside view cells sees.
  r.inside.assign(n, 0);
  r.pvs.assign(n, {});
  if (!flow_cells.empty()) r.flow_cells.assign(n, {});
  for (std::size_t v = 0; v < nv; ++v) {
    const std::size_t c = regions ? regions->cell_of[v] : v;
    if (!view_inside[v]) continue;
    r.inside[c] = 1;
    r.pvs[c] = r.pvs[c].empty() ? std::move(pvs[v]) : united(r.pvs[c], pvs[v]);
    if (flow_cells.empty()) continue;
    for (const auto d : flow_cells[v]) r.flow_cells[c].push_back(regions ? regions->cell_of[d] : d);
  }
  for (auto& cells : r.flow_cells) {
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  }
  r.seconds_pvs = since(t);
  // Per cell, for -v: counting detail items walks every PVS, so only when the line is logged.
  for (std::size_t c = 0; c < n && spdlog::should_log(spdlog::level::debug); ++c) {
    if (!r.inside[c]) continue;
    const Box& b = r.partition.cells[c];
    const auto detail = std::count_if(r.pvs[c].begin(), r.pvs[c].end(),
                                      [&](std::uint32_t p) { return r.polygons[p].detail; });
    spdlog::debug(
        "visibility: cell {} ({:.2f} {:.2f} {:.2f})..({:.2f} {:.2f} {:.2f}) reaches {} cells, PVS {} items "
        "({} detail; flow {}, samples {})",
        c, b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z,
        r.flow_cells.empty() ? 0 : r.flow_cells[c].size(), r.pvs[c].size(), detail,
        regions || flow_polys.empty() ? 0 : flow_polys[c].size(),
        regions || sampled.empty() ? 0 : sampled[c].size());
  }
  return r;
}

// The sampled PVS casts cells x sample_points x rays_per_point rays: checked once the cells are known,
// before one is cast (issue 28's work budgets), so a typo in a knob stops the compile in milliseconds.
void check_sample_budget(const VisibilityConfig& config, std::size_t cells) {
  const double rays = double(cells) * config.sample_points * config.rays_per_point;
  if (rays <= kMaxSampledPvsRays) return;
  throw Error(located(
      config.source, 0,
      fmt::format(
          "[visibility] sample_points = {} x rays_per_point = {} over {} cells would cast about {:.3g} "
          "rays, above the limit of {:.0e}",
          config.sample_points, config.rays_per_point, cells, rays, kMaxSampledPvsRays),
      fmt::format("lower sample_points x rays_per_point to at most {:.3g}",
                  kMaxSampledPvsRays / double(cells))));
}

CoarseForms coarse_forms(std::span<const model::PolygonRecord> polygons,
                         std::span<const std::uint32_t> indices,
                         std::span<const model::CoarseRangeRecord> coarse_ranges,
                         std::span<const std::uint32_t> coarse_indices) {
  CoarseForms out{{polygons.begin(), polygons.end()}, indices};
  if (coarse_ranges.size() != polygons.size()) return out;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    out.polygons[p].first_index = coarse_ranges[p].first_index;
    out.polygons[p].index_count = coarse_ranges[p].index_count;
  }
  out.indices = coarse_indices;
  return out;
}

CellsStageCounts compute_cells(model::BundleContents& out, const VisibilityConfig& config) {
  std::vector<std::string> group_names;
  for (const auto& g : out.groups) group_names.emplace_back(out.strings.c_str() + g.name);
  const CoarseForms coarse = coarse_forms(out.polygons, out.indices, out.coarse_ranges, out.coarse_indices);
  const VisibilityResult r = compute_visibility(out.vertices, coarse.indices, coarse.polygons, config,
                                                group_names, out.polygons, out.indices);
  out.clusters.clear();
  out.cluster_polygons.clear();
  for (std::size_t i = 0; i < r.polygons.size(); ++i) {
    model::ClusterRecord k{};
    for (int a = 0; a < 3; ++a) {
      k.bounds_min[a] = static_cast<float>(r.polygons[i].box.min[a]);
      k.bounds_max[a] = static_cast<float>(r.polygons[i].box.max[a]);
    }
    k.polygon_first = static_cast<std::uint32_t>(out.cluster_polygons.size());
    k.polygon_count = static_cast<std::uint32_t>(r.item_polygons[i].size());
    out.cluster_polygons.insert(out.cluster_polygons.end(), r.item_polygons[i].begin(),
                                r.item_polygons[i].end());
    out.clusters.push_back(k);
  }
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
    rec.flags = r.inside[c] ? 0u : model::kCellOutside;
    out.pvs.insert(out.pvs.end(), r.pvs[c].begin(), r.pvs[c].end());
    out.cells.push_back(rec);
  }
  // Portals as boxes rounded outward to float, so the renderer's narrowing through them stays conservative.
  out.portals.clear();
  for (const Portal& portal : r.graph.portals) {
    model::PortalRecord rec{};
    rec.back = portal.back;
    rec.front = portal.front;
    rec.flags = std::uint32_t(portal.axis) | (portal.forward ? model::kPortalForward : 0u) |
                (portal.backward ? model::kPortalBackward : 0u);
    for (int a = 0; a < 3; ++a) {
      double lo = std::numeric_limits<double>::max(), hi = -lo;
      for (const model::Vec3& p : portal.outline.front()) {
        lo = std::min(lo, p[a]);
        hi = std::max(hi, p[a]);
      }
      rec.bounds_min[a] = round_down(lo);
      rec.bounds_max[a] = round_up(hi);
    }
    if (portal.forward || portal.backward) out.portals.push_back(rec);
  }
  // The largest few openings are named, with the way in from a seed; the count is in the stage detail.
  auto world = [&](const model::Vec3& p) {
    return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x + out.meta.origin[0], p.y + out.meta.origin[1],
                       p.z + out.meta.origin[2]);
  };
  for (std::size_t i = 0; i < std::min<std::size_t>(r.leaks.size(), 3); ++i) {
    const LeakPath& leak = r.leaks[i];
    std::string path;
    for (const auto& p : leak.points) path += (path.empty() ? "" : " -> ") + world(p);
    spdlog::warn("visibility: leak to the outside, {:.4f} m2 at world {}{}", leak.area,
                 world(leak.points.back()), r.seeded ? "; path from inside: " + path : std::string());
  }
  out.void_facing = r.polygons_of(r.void_facing);
  out.leak_path.clear();
  if (r.seeded && !r.leaks.empty())
    for (const auto& p : r.leaks.front().points)
      out.leak_path.push_back({float(p.x), float(p.y), float(p.z)});
  const DrawOrderCounts order = order_for_cells(out, config.threads);
  return {out.polygons.size(), out.cells.size(),
          std::string(pvs_method_name(config.method)) + ": " + r.summary() +
              fmt::format("; draw ranges {} -> {} over all cells", order.ranges_before, order.ranges_after)};
}

}  // namespace walk::compiler
