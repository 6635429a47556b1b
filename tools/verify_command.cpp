// walk verify visibility x.walk: the bundle's PVS against ID images ray cast over the full model, and with
// --sweep, what each PVS method and sample count costs in precompute time against missed pixels and size.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/progress.hpp"
#include "compiler/partition/portals.hpp"
#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/verify_visibility.hpp"
#include "model/bundle.hpp"
#include "tools/commands.hpp"

namespace walk::tools {
namespace verify_command {  // named: walk compiles its commands as one unit

using namespace walk::compiler;

struct VerifyArgs {
  std::string bundle;
  VerifyOptions options;
  std::string sweep;                                        // CSV path; empty: verify the bundle's own PVS
  double threshold = VisibilityConfig{}.threshold;          // the sweep's partition threshold: the scene's
  double min_cell_size = VisibilityConfig{}.min_cell_size;  // and its thinnest cell
  bool quiet = false;
  std::vector<std::uint32_t> cells;  // judge only these (to look into a cell's misses); empty: all
};

std::vector<std::vector<std::uint32_t>> bundle_pvs(const model::Bundle& b) {
  std::vector<std::vector<std::uint32_t>> out;
  for (std::uint32_t c = 0; c < b.cells().size(); ++c) out.push_back(b.cell_polygons(c));
  return out;
}

VerifyRow judge_cell(const VisibilityJudge& judge, const CellViews& views,
                     const std::vector<std::uint32_t>& pvs, std::uint32_t cell) {
  VerifyRow row;
  row.cell = cell;
  row.pvs = pvs.size();
  row.exact = views.exact.size();
  row.missed = judge.missed(views, pvs);
  row.pixels = views.offsets.size() - 1;
  return row;
}

VerifyReport report_of(std::vector<VerifyRow> rows, std::size_t polygons) {
  VerifyReport r;
  r.rows = std::move(rows);
  r.polygons = polygons;
  r.cells = r.rows.size();
  summarise(r);
  return r;
}

VerifyReport judge(const VisibilityJudge& judge, const std::vector<CellViews>& views,
                   const std::vector<std::vector<std::uint32_t>>& pvs) {
  std::vector<VerifyRow> rows;
  for (std::uint32_t c = 0; c < views.size(); ++c) rows.push_back(judge_cell(judge, views[c], pvs[c], c));
  return report_of(std::move(rows), judge.polygon_count());
}

// The first polygon behind a missed pixel of the cell, with where it is, to find the cause; empty if none.
std::string first_missed(const VisibilityJudge& judge, const CellViews& views,
                         const std::vector<std::uint32_t>& pvs) {
  for (std::size_t px = 0; px + 1 < views.offsets.size(); ++px)
    for (std::uint32_t i = views.offsets[px]; i < views.offsets[px + 1]; ++i) {
      const auto id = views.ids[i];
      if (std::binary_search(pvs.begin(), pvs.end(), id)) continue;
      const auto& p = judge.polygons()[id];
      // The eye whose images hold this pixel: the last that starts at or before it.
      model::Vec3 eye{0.0};
      for (const auto& [at, first] : views.eyes)
        if (first <= px) eye = at;
      char text[240];
      std::snprintf(text, sizeof text,
                    " [polygon %u at (%.2f %.2f %.2f)..(%.2f %.2f %.2f) seen from (%.9g %.9g %.9g)]", id,
                    p.box.min.x, p.box.min.y, p.box.min.z, p.box.max.x, p.box.max.y, p.box.max.z, eye.x,
                    eye.y, eye.z);
      return text;
    }
  return {};
}

int verify(const VerifyArgs& args) {
  const auto b = model::Bundle::open(args.bundle);
  const VisibilityJudge j(b->vertices(), b->indices(), b->polygons(), args.options, b->void_facing());
  const BundleCells cells = bundle_cells(j.polygons(), b->cells(), args.options.cull_back_faces);
  const Partition& part = cells.partition;
  const PortalGraph& graph = cells.graph;

  // A sweep judges every setting against the same images, so it keeps them all; checking the bundle's own
  // PVS judges each cell as soon as it is looked at and keeps only the verdict (the full-size images of a
  // 21-cell house are over a gigabyte of ids).
  const bool keep_images = !args.sweep.empty();
  const auto pvs = bundle_pvs(*b);
  // Without clusters PVSL lists polygons, and the polygon ratio is the only one.
  const std::vector<std::uint32_t> cluster_of =
      b->clusters().empty() ? std::vector<std::uint32_t>()
                            : cluster_of_polygons(b->polygons().size(), b->clusters(), b->cluster_polygons());
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<CellViews> views;
  std::vector<VerifyRow> rows;
  std::vector<std::string> missed_at;
  std::size_t portal_eyes = 0;
  std::size_t off_walk = 0;
  Progress progress("verify: cell views", part.cells.size(), "cells");
  for (std::uint32_t c = 0; c < part.cells.size(); ++c) {
    progress.advance();
    // Off the walk (only the outside reaches it): no viewer stands there and the renderer draws everything.
    const bool asked =
        args.cells.empty() || std::find(args.cells.begin(), args.cells.end(), c) != args.cells.end();
    if (!keep_images && (!asked || (b->cells()[c].flags & model::kCellOutside))) {
      ++off_walk;
      views.emplace_back();
      missed_at.emplace_back();
      continue;
    }
    CellViews v = j.views(part.cells[c], c, portal_viewpoints(graph, part.cells[c], c));
    portal_eyes += v.portal_viewpoints;
    if (!keep_images) {
      rows.push_back(judge_cell(j, v, pvs[c], c));
      if (!cluster_of.empty()) {
        rows.back().pvs_clusters = b->cells()[c].pvs_count;
        rows.back().exact_clusters = clusters_holding(v.exact, cluster_of);
      }
      missed_at.push_back(rows.back().missed ? first_missed(j, v, pvs[c]) : std::string());
      v.ids = std::vector<std::uint32_t>();  // not `= {}`: that clears but keeps the capacity
      v.offsets = std::vector<std::uint32_t>();
    }
    views.push_back(std::move(v));
  }
  const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (!args.sweep.empty()) {
    std::vector<std::string> group_names;
    for (const auto& g : b->groups()) group_names.emplace_back(b->string(g.name));
    std::FILE* csv = std::fopen(args.sweep.c_str(), "w");
    if (!csv) {
      std::fprintf(stderr, "walk verify: cannot write %s\n", args.sweep.c_str());
      return 1;
    }
    std::fprintf(csv,
                 "method,points,rays_per_point,seconds,missed_pixels,pixels,pvs_avg,pvs_worst,ratio,cells,"
                 "proof_pairs\n");
    struct Setting {
      PvsMethod method;
      int points, rays, proof_pairs;
    };
    std::vector<Setting> settings;
    for (const int points : {2, 8, 32, 128}) settings.push_back({PvsMethod::Sampled, points, 256, 0});
    settings.push_back({PvsMethod::Conservative, 0, 1, 0});
    // The combined PVS by the proof's budget: what tightness costs in precompute time.
    for (const int pairs : {0, 4, 16, 64, 256, 1024})
      settings.push_back({PvsMethod::Combined, 32, 256, pairs});
    // Recomputed as the compile computes it: on the coarse forms, the display's triangles in the caster.
    const CoarseForms coarse =
        coarse_forms(b->polygons(), b->indices(), b->coarse_ranges(), b->coarse_indices());
    for (const auto& s : settings) {
      VisibilityConfig cfg;
      cfg.method = s.method;
      cfg.sample_points = s.points;
      cfg.rays_per_point = s.rays;
      cfg.proof_pairs = s.proof_pairs;
      cfg.min_cell_size = args.min_cell_size;
      cfg.threads = args.options.threads;
      cfg.threshold = args.threshold;
      cfg.cull_back_faces = args.options.cull_back_faces;
      const auto t = std::chrono::steady_clock::now();
      const VisibilityResult vr = compute_visibility(b->vertices(), coarse.indices, coarse.polygons, cfg,
                                                     group_names, b->polygons(), b->indices());
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
      if (vr.partition.cells.size() != views.size()) {
        std::fprintf(stderr,
                     "walk verify: --sweep recomputed %zu cells where the bundle has %zu: pass the scene's "
                     "[visibility] threshold and min_cell_size with --threshold and --min-cell-size\n",
                     vr.partition.cells.size(), views.size());
        std::fclose(csv);
        return 1;
      }
      std::vector<std::vector<std::uint32_t>> pvs;
      for (std::size_t c = 0; c < vr.pvs.size(); ++c) pvs.push_back(vr.polygon_pvs(c));
      const VerifyReport r = judge(j, views, pvs);
      std::fprintf(csv, "%s,%d,%d,%.3f,%llu,%llu,%.1f,%llu,%.3f,%zu,%d\n", pvs_method_name(s.method),
                   s.points, s.rays, seconds, static_cast<unsigned long long>(r.missed),
                   static_cast<unsigned long long>(r.pixels), r.pvs_average,
                   static_cast<unsigned long long>(r.pvs_worst), r.ratio, r.cells, s.proof_pairs);
      std::printf(
          "%-12s points %4d rays %4d proof pairs %4d: %7.2f s, missed %llu of %llu pixels, PVS avg %.1f, "
          "PVS/exact %.3f\n",
          pvs_method_name(s.method), s.points, s.rays, s.proof_pairs, seconds,
          static_cast<unsigned long long>(r.missed), static_cast<unsigned long long>(r.pixels), r.pvs_average,
          r.ratio);
    }
    std::fclose(csv);
    return 0;
  }

  // Cells inside walls are listed, not judged (cells_to_judge).
  std::vector<bool> no_open_space;
  for (const auto& row : rows) no_open_space.push_back(views[row.cell].no_free_space);
  const std::vector<bool> judged = cells_to_judge(no_open_space);
  std::vector<std::uint32_t> inside_walls;
  std::vector<VerifyRow> judged_rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (judged[i])
      judged_rows.push_back(rows[i]);
    else
      inside_walls.push_back(rows[i].cell);
  }
  rows = std::move(judged_rows);
  VerifyReport r = report_of(std::move(rows), j.polygon_count());
  r.portals = graph.portals.size();
  if (!args.quiet)
    for (const auto c : inside_walls) std::printf("cell %4u: no open space found: not judged\n", c);
  if (!args.quiet)
    for (const auto& row : r.rows) {
      std::printf("cell %4u: PVS %6llu exact %6llu missed %llu", row.cell,
                  static_cast<unsigned long long>(row.pvs), static_cast<unsigned long long>(row.exact),
                  static_cast<unsigned long long>(row.missed));
      if (views[row.cell].no_free_space) std::printf(" (no open space found: viewpoints anywhere)");
      std::printf("%s\n", missed_at[row.cell].c_str());
    }
  std::printf(
      "bundle %s: %zu polygons, %zu cells judged (%zu off the walk, %zu with no open space found), %zu "
      "portals, "
      "leak path %s\n",
      args.bundle.c_str(), r.polygons, r.cells, off_walk, inside_walls.size(), r.portals,
      b->leak_path().empty() ? "none" : (std::to_string(b->leak_path().size()) + " points").c_str());
  std::printf(
      "viewpoints per cell %d at %dx%d x6, dense %d^3 and %zu beside portals in all at %dx%d x6 (%.1f s)\n",
      args.options.viewpoints, args.options.resolution, args.options.resolution, args.options.dense,
      portal_eyes, args.options.dense_resolution, args.options.dense_resolution, render_s);
  std::printf("missed pixels %llu of %llu\n", static_cast<unsigned long long>(r.missed),
              static_cast<unsigned long long>(r.pixels));
  std::printf("PVS / exact %.3f (worst cell %.3f)\n", r.ratio, r.ratio_worst);
  std::printf("polygons drawn average %.1f worst %llu (exact average %.1f)\n", r.pvs_average,
              static_cast<unsigned long long>(r.pvs_worst), r.exact_average);
  std::printf("reduction factor %.2f\n", r.reduction);
  if (!cluster_of.empty())
    std::printf("PVS / exact clusters %.3f (worst cell %.3f): %.1f clusters drawn on average, exact %.1f\n",
                r.cluster_ratio, r.cluster_ratio_worst, r.cluster_pvs_average, r.cluster_exact_average);
  return r.missed == 0 ? 0 : 2;
}

}  // namespace verify_command

void add_verify_command(CLI::App& app, int& exit_code) {
  using namespace verify_command;
  auto* verify_cmd = app.add_subcommand("verify", "Check a bundle against ground truth");
  verify_cmd->require_subcommand(1);
  auto args = std::make_shared<VerifyArgs>();
  auto* cmd = verify_cmd->add_subcommand(
      "visibility", "PVS vs polygon-ID cube images from random viewpoints per cell; exit 2 on missed pixels");
  cmd->add_option("bundle", args->bundle, "Bundle to verify")->required();
  cmd->add_option("--viewpoints", args->options.viewpoints, "Random viewpoints per cell")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--resolution", args->options.resolution, "Cube face size in pixels")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--dense", args->options.dense, "Dense viewpoints per axis per cell (n^3)")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--dense-resolution", args->options.dense_resolution, "Cube face size for dense viewpoints")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--ray-caster", args->options.ray_caster, "Ray caster for the ID images");
  cmd->add_option("--threads", args->options.threads, "Threads (0: all cores)");
  cmd->add_option("--sweep", args->sweep, "Sweep PVS methods and sample counts; write CSV here");
  cmd->add_option("--threshold", args->threshold,
                  "Partition threshold the sweep recomputes cells with: the scene's [visibility] threshold");
  cmd->add_option("--min-cell-size", args->min_cell_size,
                  "Thinnest cell the sweep recomputes cells with: the scene's [visibility] min_cell_size")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("-q,--quiet", args->quiet, "No per-cell lines");
  cmd->add_option("--cells", args->cells,
                  "Judge only these cells (the others count as off the walk), to look into their misses")
      ->delimiter(',');
  cmd->add_flag("--two-sided{false}", args->options.cull_back_faces,
                "Judge as if the renderer drew both sides of every polygon (default: back faces culled, as "
                "it draws them)");
  cmd->add_flag(
      "--anywhere{false}", args->options.free_space_only,
      "Viewpoints anywhere in a cell, also inside solids and outside the model (default: open space)");
  cmd->add_flag("--pixel-centres{false}", args->options.jitter,
                "Sight lines through pixel centres (default: a random point in each pixel)");
  cmd->add_flag("--no-portal-views{false}", args->options.portal_views,
                "No viewpoints beside the portals (default: each portal's centre and corners, 1 mm inside "
                "each cell it joins, at the dense resolution)");
  cmd->callback([args, &exit_code] { exit_code = verify(*args); });
}

}  // namespace walk::tools
