// walk bench render scene.toml|x.walk...: frame times at 1280x720 along a scripted walk, culled and unculled,
// with the governor holding the target rate while moving, and what each refinement level, the compact light
// form and each anti-aliasing sample count costs. One CSV table on stdout.
#include <fmt/format.h>
#include <glad/gl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <glm/geometric.hpp>
#include <iostream>
#include <numeric>
#include <optional>
#include <sstream>

#include "common/progress.hpp"
#include "compiler/pipeline.hpp"
#include "model/bundle.hpp"
#include "model/error.hpp"
#include "render/backend/backend.hpp"
#include "render/frame_timing.hpp"
#include "render/renderer.hpp"
#include "render/tonemap.hpp"
#include "tools/commands.hpp"
#include "tools/gnuplot.hpp"
#include "tools/option_vectors.hpp"
#include "tools/shading_count.hpp"

namespace walk::tools {
namespace bench_render_command {  // named: walk compiles its commands as one unit

using Clock = std::chrono::steady_clock;

struct Options {
  std::vector<std::string> inputs;
  std::string plot;
  std::string size = "1280x720";
  std::string backend = "auto";
  int frames = 240;
  double target_hz = 60.0;
  std::string frame_timing = "auto";
  bool portals = true;        // the governed, level and AA sections walk the portals (the kiosk's default)
  bool occlusion = true;      // ... and cull by occlusion (the kiosk's default)
  bool blit_upscale = false;  // the half-resolution level scaled up by a GL blit even on a software GL
};

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Nearest rank on the sorted times.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

// Whether the kiosk's viewer can stand at `eye`: in a cell on the walk (anywhere when the bundle has no
// cells).
bool is_on_walk(const model::Bundle& bundle, const glm::dvec3& eye) {
  if (bundle.cells().empty()) return true;
  const double at[3] = {eye.x, eye.y, eye.z};
  const std::uint32_t cell = bundle.locate_cell(at);
  return cell < bundle.cells().size() && !(bundle.cells()[cell].flags & model::kCellOutside);
}

// The scripted walk: eye 1.2 m under each luminaire (inside a room by construction), visited nearest first,
// straight segments between them, looking where it goes, turning a little as it walks. Segments between
// rooms that are not neighbours pass through walls, where the kiosk's viewer never stands (navigation
// collides with them): points off the walk (in no cell, or in one only the outside reaches, where every
// polygon is drawn) are left out, and the frames spread over the rest. Not a navigation test.
std::vector<render::View> scripted_walk(const model::Bundle& bundle, int frames) {
  std::vector<glm::dvec3> stops;
  for (const auto& l : bundle.luminaires())
    stops.push_back({l.position[0], l.position[1], l.position[2] - 1.2});
  if (stops.size() < 2) {
    const auto& m = bundle.meta();
    const glm::dvec3 lo{m.bounds_min[0], m.bounds_min[1], m.bounds_min[2]};
    const glm::dvec3 hi{m.bounds_max[0], m.bounds_max[1], m.bounds_max[2]};
    stops = {lo + (hi - lo) * glm::dvec3(0.25, 0.5, 0.0) + glm::dvec3(0, 0, 1.6),
             lo + (hi - lo) * glm::dvec3(0.75, 0.5, 0.0) + glm::dvec3(0, 0, 1.6)};
  }
  std::vector<glm::dvec3> path{stops.front()};
  std::vector<bool> used(stops.size(), false);
  used[0] = true;
  for (std::size_t k = 1; k < std::min<std::size_t>(stops.size(), 16); ++k) {
    std::size_t best = 0;
    double best_d = 1e300;
    for (std::size_t i = 0; i < stops.size(); ++i)
      if (!used[i] && glm::length(stops[i] - path.back()) < best_d)
        best_d = glm::length(stops[i] - path.back()), best = i;
    used[best] = true;
    path.push_back(stops[best]);
  }
  std::vector<double> along{0.0};
  for (std::size_t i = 1; i < path.size(); ++i)
    along.push_back(along.back() + glm::length(path[i] - path[i - 1]));
  // The segment (its end's index) and point at distance `s` along the path.
  auto point_at = [&](double s) {
    std::size_t i = 1;
    while (i + 1 < path.size() && along[i] < s) ++i;
    const double t = along[i] > along[i - 1] ? (s - along[i - 1]) / (along[i] - along[i - 1]) : 0.0;
    return std::pair{i, path[i - 1] + (path[i] - path[i - 1]) * std::clamp(t, 0.0, 1.0)};
  };
  // Points on the walk, kOversample times as many as frames, then `frames` of them evenly.
  constexpr int kOversample = 8;
  const int samples = frames * kOversample;
  std::vector<double> on_walk, every;
  for (int j = 0; j < samples; ++j) {
    every.push_back(along.back() * j / std::max(1, samples - 1));
    if (is_on_walk(bundle, point_at(every.back()).second)) on_walk.push_back(every.back());
  }
  if (on_walk.size() < 2) on_walk = every;  // none on this path: every point
  if (on_walk.size() < every.size())
    std::cerr << "scripted walk: " << every.size() - on_walk.size() << " of " << every.size()
              << " points along its path are off the walk (in walls or the void) and left out\n";
  std::vector<render::View> views;
  for (int f = 0; f < frames; ++f) {
    const auto [i, eye] = point_at(
        on_walk[std::size_t(std::llround(double(on_walk.size() - 1) * f / std::max(1, frames - 1)))]);
    render::View v;
    v.eye = eye;
    glm::dvec3 d = path[i] - path[i - 1];
    d.z = 0.0;
    if (glm::length(d) < 1e-9) d = {1, 0, 0};
    const double turn = 0.6 * std::sin(f * 0.05);
    d = glm::normalize(d);
    v.forward = {d.x * std::cos(turn) - d.y * std::sin(turn), d.x * std::sin(turn) + d.y * std::cos(turn),
                 -0.1};
    views.push_back(v);
  }
  return views;
}

// What a frame costs in accuracy: against a reference frame of the same view, the mean absolute error in
// linear light (0..1 per channel) and the share of pixels with a channel off by more than 2/255.
struct ImageError {
  double mae_linear = 0.0;
  double over_2_percent = 0.0;
};

ImageError image_error(const render::Image& image, const render::Image& reference) {
  static const auto linear = render::srgb_decode_table();
  ImageError e;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  std::size_t over = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    bool off = false;
    for (int k = 0; k < 3; ++k) {
      const std::uint8_t a = image.rgba[i * 4 + k], b = reference.rgba[i * 4 + k];
      e.mae_linear += std::abs(double(linear[a]) - double(linear[b]));
      off = off || std::abs(int(a) - int(b)) > 2;
    }
    over += off;
  }
  e.mae_linear /= double(pixels * 3);
  e.over_2_percent = 100.0 * double(over) / double(pixels);
  return e;
}

struct Row {
  std::string section, variant;
  std::size_t frames = 0;
  double p50 = 0.0, p99 = 0.0, polygons = 0.0, triangles = 0.0;
  std::optional<ImageError> error;
  std::string note;
};

void print(const std::string& scene, const Row& r) {
  std::printf("%s,%s,%s,%zu,%.2f,%.2f,%.0f,%.0f,", scene.c_str(), r.section.c_str(), r.variant.c_str(),
              r.frames, r.p50, r.p99, r.polygons, r.triangles);
  if (r.error)
    std::printf("%.5f,%.2f,", r.error->mae_linear, r.error->over_2_percent);
  else
    std::printf(",,");
  std::printf("%s\n", r.note.c_str());
}

// One model's place on the size plot.
struct Summary {
  std::string scene;
  std::size_t triangles = 0;
  double walk_p50 = 0.0, walk_p99 = 0.0;  // culled + frustum + portals + occlusion, patches
  double governed_p50 = 0.0, governed_p99 = 0.0;
};

Summary run_one(const Options& o, const std::string& input, int width, int height, bool header) {
  Summary summary;
  std::string path = input;
  std::filesystem::path temp;
  if (std::filesystem::path(input).extension() == ".toml") {
    temp = std::filesystem::temp_directory_path() / ("walk_bench_render_" + std::to_string(::getpid()));
    std::filesystem::create_directories(temp);
    path = (temp / "scene.walk").string();
    std::cerr << "compiling " << input << "\n";
    compiler::compile_to_file(input, path, true);
  }
  const std::string scene = std::filesystem::path(input).stem().string();
  summary.scene = scene;
  {
    auto bundle = model::Bundle::open(path);
    render::BackendOptions bo;
    bo.kind = render::parse_backend_kind(o.backend);
    bo.width = width;
    bo.height = height;
    auto backend = render::Backend::create(bo);
    backend->make_current();
    render::Renderer renderer(*bundle);
    const std::optional<bool> cpu_upscale = o.blit_upscale ? std::optional(false) : std::nullopt;
    renderer.set_cpu_upscale(cpu_upscale);
    const auto walk = scripted_walk(*bundle, o.frames);
    Progress progress("bench render " + scene, 0, "frames");
    std::cerr << "backend " << backend->name() << ", " << bundle->polygons().size() << " polygons, "
              << bundle->cells().size() << " cells, " << bundle->circuits().size() << " circuits\n";
    summary.triangles = bundle->indices().size() / 3;
    if (header)
      std::printf(
          "scene,section,variant,frames,p50_ms,p99_ms,mean_polygons,mean_triangles,mae_linear,pixels_over_2_"
          "pct,"
          "note\n");

    // Unculled, then each culling on top of the one before, along the same walk, alternating view by view so
    // that the machine's noise falls on every variant alike; each frame drawn and finished.
    constexpr int kVariants = 5;
    const char* names[kVariants] = {"unculled", "culled", "culled+frustum", "culled+frustum+portals",
                                    "culled+frustum+portals+occlusion"};
    auto set_variant = [&](int k) {
      renderer.set_pvs_culling(k >= 1);
      renderer.set_frustum_culling(k >= 2);
      renderer.set_portal_culling(k >= 3);
      renderer.set_occlusion_culling(k >= 4);
    };
    std::array<std::vector<double>, kVariants> walk_times;
    std::array<double, kVariants> walk_polygons{}, walk_triangles{}, cells_seen{};
    for (int k = 0; k < kVariants; ++k) {
      set_variant(k);
      renderer.draw(walk.front(), width, height);
      glFinish();
    }
    for (const auto& v : walk) {
      for (int k = 0; k < kVariants; ++k) {
        set_variant(k);
        const auto t0 = Clock::now();
        renderer.draw(v, width, height);
        glFinish();
        walk_times[std::size_t(k)].push_back(ms_since(t0));
        walk_polygons[std::size_t(k)] += renderer.last_stats().polygons_drawn;
        walk_triangles[std::size_t(k)] += renderer.last_stats().triangles_drawn;
        cells_seen[std::size_t(k)] += renderer.last_stats().cells_seen;
      }
      progress.advance();
    }
    std::array<double, kVariants> p50{};
    for (int k = 0; k < kVariants; ++k) {
      const auto& t = walk_times[std::size_t(k)];
      p50[std::size_t(k)] = percentile(t, 0.5);
      if (k == kVariants - 1) summary.walk_p50 = p50[std::size_t(k)], summary.walk_p99 = percentile(t, 0.99);
      const double n = double(walk.size());
      print(scene,
            {"walk",
             names[k],
             t.size(),
             p50[std::size_t(k)],
             percentile(t, 0.99),
             walk_polygons[std::size_t(k)] / n,
             walk_triangles[std::size_t(k)] / n,
             {},
             k >= 3 ? fmt::format("patches; draw + glFinish; {:.1f} cells seen through portals on average",
                                  cells_seen[std::size_t(k)] / n)
                    : std::string("patches; draw + glFinish")});
    }
    for (int k = 1; k < kVariants; ++k)
      print(scene, {"walk",
                    std::string("speedup-") + names[k],
                    walk.size(),
                    p50[0] / std::max(1e-9, p50[std::size_t(k)]),
                    0,
                    0,
                    0,
                    {},
                    std::string("p50 unculled / p50 ") + names[k]});
    renderer.set_frustum_culling(true);  // the kiosk's default from here on
    renderer.set_portal_culling(o.portals);
    renderer.set_occlusion_culling(o.occlusion);

    // Governed: refine() every frame while moving, culled; the governor picks coarse or patches per cell.
    renderer.set_pvs_culling(true);
    renderer.set_target_rate(o.target_hz);
    renderer.set_frame_timing(*render::parse_frame_timing(o.frame_timing));
    std::vector<double> times;
    double polygons = 0.0, triangles = 0.0;
    std::array<int, render::kMovingLevels> at_level{};
    for (int pass = 0; pass < 2; ++pass) {  // the first pass teaches the governor each cell's cost
      times.clear();
      polygons = triangles = 0.0;
      at_level.fill(0);
      for (const auto& v : walk) {
        const auto t0 = Clock::now();
        renderer.refine(v, width, height);
        glFinish();  // as presenting would: a frame timed by queries has only been submitted
        times.push_back(ms_since(t0));
        polygons += renderer.last_stats().polygons_drawn;
        triangles += renderer.last_stats().triangles_drawn;
        ++at_level[std::size_t(renderer.last_stats().moving_level)];
      }
    }
    const double budget = 1000.0 / o.target_hz;
    summary.governed_p50 = percentile(times, 0.5);
    summary.governed_p99 = percentile(times, 0.99);
    print(scene,
          {"governed",
           "moving",
           times.size(),
           percentile(times, 0.5),
           percentile(times, 0.99),
           polygons / double(walk.size()),
           triangles / double(walk.size()),
           {},
           std::to_string(at_level[0]) + " half-res + " + std::to_string(at_level[1]) + " simplified + " +
               std::to_string(at_level[2]) + " coarse + " + std::to_string(at_level[3]) +
               " patch frames; target " + std::to_string(int(budget * 100) / 100.0).substr(0, 5) +
               " ms; p99 " + (percentile(times, 0.99) <= budget ? "within" : "OVER")});

    // Each level along the walk (every kLevelViewStride-th view): its frame time, triangles and image error
    // against the full-detail frame (patches, every triangle, full size) of the same view.
    struct Level {
      const char* name;
      render::DrawOptions options;
    };
    const render::DrawOptions full{};
    const std::vector<Level> levels{
        {"reduced-half-res",
         {.patch_weight = 0.0f, .resolution = 0.5f, .lod_pixels = render::kReducedErrorPixels}},
        {"simplified", {.patch_weight = 0.0f, .lod_pixels = render::kSimplifiedErrorPixels}},
        {"coarse", {.patch_weight = 0.0f}},
        {"blend-0.5", {.patch_weight = 0.5f}},
        {"patches", full}};
    constexpr std::size_t kLevelViewStride = 8;
    std::vector<render::Image> reference;
    for (std::size_t i = 0; i < walk.size(); i += kLevelViewStride) {
      renderer.draw(walk[i], width, height, full);
      reference.push_back(renderer.read_pixels(width, height));
    }
    for (const Level& level : levels) {
      std::vector<double> t;
      double triangles_sum = 0.0, polygons_sum = 0.0, ranges_sum = 0.0;
      ImageError error;
      ShadingCount shaded;  // the frames only, not read_pixels
      for (std::size_t i = 0, k = 0; i < walk.size(); i += kLevelViewStride, ++k) {
        shaded.begin();
        const auto t0 = Clock::now();
        renderer.draw(walk[i], width, height, level.options);
        progress.advance();
        glFinish();
        t.push_back(ms_since(t0));
        shaded.end();
        triangles_sum += renderer.last_stats().triangles_drawn;
        polygons_sum += renderer.last_stats().polygons_drawn;
        ranges_sum += renderer.last_stats().draw_ranges;
        const ImageError e = image_error(renderer.read_pixels(width, height), reference[k]);
        error.mae_linear += e.mae_linear / double(reference.size());
        error.over_2_percent += e.over_2_percent / double(reference.size());
      }
      // Fragments include the reduced level's scaled copy to full size where a blit makes it: a full frame's
      // pixels once more.
      const double views = double(t.size());
      const std::string shading =
          ShadingCount::available()
              ? fmt::format("; {:.0f} fragments ({:.2f} a pixel) and {:.0f} vertices shaded a frame",
                            double(shaded.fragments) / views,
                            double(shaded.fragments) / views / (double(width) * double(height)),
                            double(shaded.vertices) / views)
              : std::string();
      print(scene,
            {"level", level.name, t.size(), percentile(t, 0.5), percentile(t, 0.99), polygons_sum / views,
             triangles_sum / views, error,
             std::to_string(int(ranges_sum / views)) +
                 " draw ranges; views along the walk; error against patches at full detail" + shading});
    }
    {
      // Walking while an operator turns the dimmers: the coarse level with every circuit's level changed
      // each frame, so its polygon light is mixed again on the CPU before each frame (against `coarse`).
      // Standing still while they turn: every frame a new mix at full detail (refine()).
      std::vector<float> levels(bundle->circuits().size()), defaults(levels.size());
      for (std::size_t c = 0; c < levels.size(); ++c) defaults[c] = bundle->circuits()[c].default_level;
      // `frames` frames, each at new levels (every circuit between 0.5 and 1), drawn by `frame(k)`.
      const auto time_dimming = [&](std::size_t frames, const auto& frame) {
        std::vector<double> times;
        for (std::size_t k = 0; k < frames; ++k) {
          for (std::size_t c = 0; c < levels.size(); ++c) levels[c] = (k + c) % 2 ? 1.0f : 0.5f;
          renderer.set_dimmers(levels);
          const auto t0 = Clock::now();
          frame(k);
          glFinish();
          times.push_back(ms_since(t0));
          progress.advance();
        }
        return times;
      };
      const std::size_t views = (walk.size() + kLevelViewStride - 1) / kLevelViewStride;
      const std::vector<double> t = time_dimming(views, [&](std::size_t k) {
        renderer.draw(walk[k * kLevelViewStride], width, height, {.patch_weight = 0.0f});
      });
      const render::View resting = walk[walk.size() / 2];
      while (renderer.refine(resting, width, height)) {
      }
      const std::vector<double> t_still =
          time_dimming(views, [&](std::size_t) { (void)renderer.refine(resting, width, height); });
      renderer.set_dimmers(defaults);
      while (renderer.refine(resting, width, height)) {
      }
      print(scene, {"level",
                    "still-dimming",
                    t_still.size(),
                    percentile(t_still, 0.5),
                    percentile(t_still, 0.99),
                    0,
                    0,
                    {},
                    "a still view, every circuit's level changed each frame (refine())"});
      print(scene, {"level",
                    "coarse-dimming",
                    t.size(),
                    percentile(t, 0.5),
                    percentile(t, 0.99),
                    0,
                    0,
                    {},
                    fmt::format("coarse with the {} circuits' levels changed each frame", levels.size())});
    }
    {
      // The floor under every level: a frame with nothing in view (clear, blit and finish), and the same
      // frame with the coarsest level of every cluster forced (every error allowed).
      render::View empty = walk.front();
      empty.eye.z = bundle->meta().bounds_max[2] + 100.0;
      empty.forward = {0.0, 0.0, 1.0};
      empty.up = {1.0, 0.0, 0.0};
      for (const auto& [name, view, lod] : {std::tuple{"empty-frame", empty, 0.0f},
                                            std::tuple{"coarsest-lod", walk[walk.size() / 2], 1e9f}}) {
        std::vector<double> t;
        for (int i = 0; i < 30; ++i) {
          const auto t0 = Clock::now();
          renderer.draw(view, width, height, {.patch_weight = 0.0f, .lod_pixels = lod});
          progress.advance();
          glFinish();
          t.push_back(ms_since(t0));
        }
        print(scene, {"level",
                      name,
                      t.size(),
                      percentile(t, 0.5),
                      percentile(t, 0.99),
                      double(renderer.last_stats().polygons_drawn),
                      double(renderer.last_stats().triangles_drawn),
                      {},
                      "one view"});
      }
    }
    // An A/B of one renderer switch at each of `at` (the simplified level and full detail, or the half-res
    // level), alternating view by view (every second view) so the machine's noise falls on both alike:
    // `set(true)` is the variant, `set(false)` the one it is compared with. Prints a row for each (`note`
    // describes it from its frames' summed stats) and a speedup row (other / variant), then leaves the switch
    // as the run has it (`set(kept)`).
    struct Sums {
      double ranges = 0.0, triangles = 0.0, occluded = 0.0;
    };
    using NamedOptions = std::vector<std::pair<const char*, render::DrawOptions>>;
    const NamedOptions simplified_and_patches{
        {"simplified", {.patch_weight = 0.0f, .lod_pixels = render::kSimplifiedErrorPixels}},
        {"patches", full}};
    const auto plain_note = [](const Sums&, double) { return std::string("alternating view by view"); };
    auto alternate =
        [&](const char* section, const char* variant, const char* other, const char* speedup,
            const char* ratio, const std::function<void(bool)>& set, bool kept, bool triangles_column,
            const std::function<std::string(const Sums&, double views)>& note, const NamedOptions& at) {
          constexpr std::size_t kViewStride = 2;
          for (const auto& [name, options] : at) {
            std::array<std::vector<double>, 2> t;  // variant, other
            std::array<Sums, 2> sums{};
            for (std::size_t i = 0; i < walk.size(); i += kViewStride)
              for (const int turn : {0, 1}) {
                // Each goes first in every other view: the second draw of a view reuses its portal walk
                // and occlusion buffer (made once a view), so always drawing one first would bill it alone.
                const int k = (i / kViewStride) % 2 == 0 ? turn : 1 - turn;
                set(k == 0);
                const auto t0 = Clock::now();
                renderer.draw(walk[i], width, height, options);
                glFinish();
                t[std::size_t(k)].push_back(ms_since(t0));
                const auto& st = renderer.last_stats();
                sums[std::size_t(k)].ranges += st.draw_ranges;
                sums[std::size_t(k)].triangles += st.triangles_drawn;
                sums[std::size_t(k)].occluded += st.triangles_occluded;
                progress.advance();
              }
            set(kept);
            const double views = double(t[0].size());
            for (const int k : {0, 1})
              print(scene, {section,
                            fmt::format("{}-{}", k == 0 ? variant : other, name),
                            t[std::size_t(k)].size(),
                            percentile(t[std::size_t(k)], 0.5),
                            percentile(t[std::size_t(k)], 0.99),
                            0,
                            triangles_column ? sums[std::size_t(k)].triangles / views : 0.0,
                            {},
                            note(sums[std::size_t(k)], views)});
            print(scene, {section,
                          fmt::format("{}-{}", speedup, name),
                          t[0].size(),
                          percentile(t[1], 0.5) / std::max(1e-9, percentile(t[0], 0.5)),
                          percentile(t[1], 0.99) / std::max(1e-9, percentile(t[0], 0.99)),
                          0,
                          0,
                          {},
                          fmt::format("{}: p50 column at p50, p99 column at p99", ratio)});
          }
        };
    // Draw order: opaque clusters nearest first (the kiosk's default) against the compiler's order (fewer,
    // merged ranges). Same pixels (NearestFirstFrameEqualsCompilerOrderFrame); the difference is the shading
    // llvmpipe's early depth test spares, which its fragment count does not show (it counts before the test).
    alternate(
        "order", "nearest-first", "compiler-order", "speedup-nearest-first", "compiler order / nearest first",
        [&](bool on) { renderer.set_nearest_first(on); }, true, false,
        [](const Sums& s, double views) {
          return fmt::format("{:.0f} draw ranges; alternating view by view", s.ranges / views);
        },
        simplified_and_patches);
    // Occlusion culling: the nearest walls rasterised into a small software depth buffer and the clusters
    // they hide left out (the kiosk's default), against drawing what the PVS, frustum and portals leave. Same
    // pixels (OcclusionCulledFrameEqualsUnculledFrame).
    alternate(
        "occlusion", "occlusion-culled", "unculled", "speedup-occlusion", "unculled / occlusion culled",
        [&](bool on) { renderer.set_occlusion_culling(on); }, o.occlusion, true,
        [](const Sums& s, double views) {
          return fmt::format("{:.0f} triangles hidden a frame; alternating view by view", s.occluded / views);
        },
        simplified_and_patches);
    // Detail elision at the moving levels with a pixel budget: clusters whose whole box spans under it left
    // out (the kiosk's default) against drawn at their coarsest level.
    alternate("elision", "elided", "drawn", "speedup-elided", "drawn / elided",
              [&](bool on) { renderer.set_detail_elision(on); }, true, true, plain_note,
              {{"simplified", simplified_and_patches.front().second}, {"half-res", levels.front().options}});
    // The half-resolution level's scaling up: read back, doubled on the CPU and uploaded (upscale.hpp; the
    // default on a software GL) against a GL_LINEAR blit. Within 1 in a channel
    // (CpuUpscaleIsWithinOneOfTheBlitAndOddSizesBlit).
    alternate("upscale", "cpu-upscale", "blit", "speedup-cpu-upscale", "blit / CPU upscale",
              [&](bool on) { renderer.set_cpu_upscale(on); }, true, false, plain_note,
              {{"half-res", levels.front().options}});
    renderer.set_cpu_upscale(cpu_upscale);
    // The coarse form's vertices shared between polygons, each triangle's flat light from a vertex of its
    // own polygon (the kiosk's default), against each polygon's own vertices. Same pixels
    // (SharedCoarseVerticesDrawTheSameFrame); the difference is the vertex work, which llvmpipe does on
    // the thread that sets up the triangles.
    if (!bundle->coarse_indices().empty())
      alternate("vertices", "shared", "own", "speedup-shared", "own / shared",
                [&](bool on) { renderer.set_shared_coarse_vertices(on); }, true, true, plain_note,
                {{levels[0].name, levels[0].options},
                 {levels[1].name, levels[1].options},
                 {levels[2].name, levels[2].options}});
    {
      // The light as the compiler chose it per circuit (compact where within its limit) against every
      // circuit full: frame time, display memory and image error, alternating view by view.
      render::Renderer full_light(*bundle, render::DisplayLightForm::Full);
      full_light.set_pvs_culling(true);
      full_light.set_frustum_culling(true);
      full_light.set_portal_culling(o.portals);
      full_light.set_occlusion_culling(o.occlusion);
      const render::DisplayLight as_compiled(*bundle, render::DisplayLightForm::AsCompiled),
          every_full(*bundle, render::DisplayLightForm::Full);
      std::vector<double> t_compiled, t_full;
      ImageError error;
      std::size_t views = 0;
      for (std::size_t i = 0; i < walk.size(); i += kLevelViewStride, ++views) {
        for (render::Renderer* r : {&renderer, &full_light}) {
          const auto t0 = Clock::now();
          r->draw(walk[i], width, height, full);
          glFinish();
          (r == &renderer ? t_compiled : t_full).push_back(ms_since(t0));
          progress.advance();
        }
        const ImageError e =
            image_error(renderer.read_pixels(width, height), full_light.read_pixels(width, height));
        error.mae_linear += e.mae_linear;
        error.over_2_percent += e.over_2_percent;
      }
      error.mae_linear /= double(std::max<std::size_t>(views, 1));
      error.over_2_percent /= double(std::max<std::size_t>(views, 1));
      const double mib = 1.0 / (1024.0 * 1024.0);
      print(scene,
            {"light", "as-compiled", t_compiled.size(), percentile(t_compiled, 0.5),
             percentile(t_compiled, 0.99), 0, 0, error,
             fmt::format("{} of {} circuits compact; light {:.1f} MiB of display memory; error against "
                         "full",
                         as_compiled.compact_circuits().size(), bundle->circuits().size(),
                         double(as_compiled.gpu_bytes()) * mib)});
      print(scene,
            {"light",
             "full",
             t_full.size(),
             percentile(t_full, 0.5),
             percentile(t_full, 0.99),
             0,
             0,
             {},
             fmt::format("every circuit from LGHT; light {:.1f} MiB of display memory (LGHT {:.1f})",
                         double(every_full.gpu_bytes()) * mib, double(every_full.full_form_bytes()) * mib)});
    }
    const render::View still = walk[walk.size() / 2];
    for (int samples : {1, 4, 16, 64}) {
      renderer.set_refine_settings({.blend_steps = 0, .aa_samples = samples, .samples_per_frame = 1});
      renderer.set_moving_level(render::MovingLevel::Patches);
      (void)renderer.refine(still, width, height);  // the moving frame
      glFinish();
      // Diagonals and subdivision under the current mix, a time slice a frame until every cluster the
      // still view may draw is made.
      std::vector<double> slices;
      do {
        const auto t0 = Clock::now();
        (void)renderer.refine(still, width, height);
        slices.push_back(ms_since(t0));
      } while (renderer.schedule_stage() == render::RefineStage::Diagonals);
      if (samples == 1) {
        const auto& st = renderer.last_stats();
        const double total = std::accumulate(slices.begin(), slices.end(), 0.0);
        print(scene,
              {"level",
               "diagonals+subdivision",
               slices.size(),
               percentile(slices, 0.5),
               *std::max_element(slices.begin(), slices.end()),
               double(st.polygons_drawn),
               double(st.triangles_drawn),
               {},
               fmt::format("{} quads flipped; {} subdivided into {} triangles, {} of them drawn with their "
                           "clusters; {} frames, {:.1f} ms in all (CPU + upload + frame); p99 column: the "
                           "longest frame",
                           st.quads_flipped, st.quads_subdivided, st.subdivision_triangles,
                           st.subdivision_triangles_drawn, slices.size(), total)});
      }
      auto t0 = Clock::now();
      while (renderer.refine(still, width, height)) {
      }
      const double total = ms_since(t0);
      print(scene, {"aa",
                    std::to_string(samples) + "-samples",
                    std::size_t(samples),
                    total / samples,
                    total,
                    double(renderer.last_stats().polygons_drawn),
                    double(renderer.last_stats().triangles_drawn),
                    {},
                    "p50 column: ms per sample; p99 column: ms to converge"});
    }
  }
  if (!temp.empty()) std::filesystem::remove_all(temp);
  return summary;
}

int run(const Options& o) {
  const auto size = parse_frame_size(o.size);
  if (!size) throw Error("--size '" + o.size + "' is not WIDTHxHEIGHT");
  const auto [width, height] = *size;
  std::ostringstream csv;
  csv << "scene,triangles,walk_p50_ms,walk_p99_ms,governed_p50_ms,governed_p99_ms\n";
  for (std::size_t i = 0; i < o.inputs.size(); ++i) {
    const Summary r = run_one(o, o.inputs[i], width, height, i == 0);
    csv << r.scene << ',' << r.triangles << ',' << r.walk_p50 << ',' << r.walk_p99 << ',' << r.governed_p50
        << ',' << r.governed_p99 << '\n';
  }
  if (!o.plot.empty()) {
    std::ostringstream commands;
    commands << "set logscale x\nset key top left\nset xlabel 'triangles in the model'\n"
             << "set ylabel 'frame ms (1280x720 unless --size)'\nset yrange [0:*]\n"
             << "set title 'Frame time against model size (walk bench render)'\n"
             << "plot '" << plot_data_path(o.plot)
             << "' every ::1 using 2:5 with linespoints title 'governed p50', "
             << "'' every ::1 using 2:6 with linespoints title 'governed p99', "
             << "'' every ::1 using 2:3 with linespoints title 'patches, PVS + frustum + portals + occlusion "
                "p50', "
             << "'' every ::1 using 2:4 with linespoints title 'patches, PVS + frustum + portals + occlusion "
                "p99', "
             << "'' every ::1 using 2:6:1 with labels offset 1,1 notitle, " << 1000.0 / o.target_hz
             << " title 'frame budget' dashtype 2\n";
    plot_with_gnuplot(o.plot, csv.str(), commands.str());
  }
  return 0;
}

}  // namespace bench_render_command

void add_bench_render_command(CLI::App& bench, int& exit_code) {
  using namespace bench_render_command;
  auto o = std::make_shared<Options>();
  auto* cmd =
      bench.add_subcommand("render", "Frame times culled/unculled, governor, refinement and AA costs (CSV)");
  cmd->add_option(
         "inputs", o->inputs,
         "Scene configs (.toml, compiled first) or bundles (.walk), one table each; several (say the "
         "generated S, M, L) for the --plot against model size")
      ->required();
  cmd->add_option(
      "--plot", o->plot,
      "Also write this PNG (and its CSV beside it): frame times against model size, with gnuplot");
  cmd->add_option("--size", o->size, "WIDTHxHEIGHT");
  cmd->add_option("--backend", o->backend, "auto, osmesa, egl, glfw or gbm");
  cmd->add_option("--frames", o->frames, "Frames along the scripted walk")->check(CLI::Range(2, 100000));
  cmd->add_option("--target-hz", o->target_hz, "Frame rate the governor holds")
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--frame-timing", o->frame_timing,
                  "How the governor times frames: auto, finish (glFinish) or queries (GL timer queries)")
      ->check([](const std::string& name) {
        return render::parse_frame_timing(name) ? std::string()
                                                : "expected " + std::string(render::kFrameTimingNames);
      });
  cmd->add_flag("--portals,!--no-portals", o->portals,
                "Walk the portals in the governed, level and AA sections (default on, as the kiosk); "
                "--no-portals draws the PVS and frustum alone, to compare runs");
  cmd->add_flag("--occlusion,!--no-occlusion", o->occlusion,
                "Cull by occlusion in the governed, level and AA sections (default on, as the kiosk); "
                "--no-occlusion draws what the PVS, frustum and portals leave, to compare runs");
  cmd->add_flag("--blit-upscale", o->blit_upscale,
                "Scale the half-resolution level up by a GL blit even on a software GL (default: on the CPU "
                "there, upscale.hpp), to compare runs; the upscale section compares both either way");
  cmd->callback([o, &exit_code] { exit_code = run(*o); });
}

}  // namespace walk::tools
