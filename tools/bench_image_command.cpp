// walk bench image: the light a still kiosk frame shows, pixel by pixel, against a path-traced reference of
// the same view. `walk bench lighting` compares the stored light at surface points; this compares what the
// viewer sees: the renderer's frame converged with anti-aliasing (diagonals, subdivision, the compact light
// form, 8-bit sRGB) read back to linear light, against compiler/lighting/path_reference's radiosity traced
// at each compared pixel's own surface points. Lamps, glass, the sky and silhouettes (pixels within one of
// an edge between polygons) are left out, as the Radiance comparison left them out.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <memory>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/lighting/drawn_triangles.hpp"
#include "compiler/lighting/path_reference.hpp"
#include "compiler/pipeline.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/bundle.hpp"
#include "model/error.hpp"
#include "model/photometric_units.hpp"
#include "model/srgb.hpp"
#include "render/backend/backend.hpp"
#include "render/camera.hpp"
#include "render/renderer.hpp"
#include "tools/commands.hpp"
#include "tools/option_vectors.hpp"

namespace walk::tools {
namespace bench_image_command {  // named: walk compiles its commands as one unit

namespace fs = std::filesystem;

struct Args {
  std::string input;  // a .walk bundle, or a scene config compiled at its own settings
  std::vector<double> eye, look;
  std::string size = "320x240";
  double fov = 60.0;
  int samples = 16;  // anti-aliasing samples of the still frame
  int pixels = 2000;
  int reference_paths = 4096;  // per pixel, over its kSubpixels points
  std::string backend = "auto";
  unsigned threads = 2;
  std::string frame;      // optional PNG of the rendered frame
  std::string error_map;  // optional PNG: each compared pixel's signed error, the rest the frame greyed
};

// A pixel's footprint is judged by a 3 x 3 grid of rays: all on one polygon, or it is a silhouette. Its
// reference is traced at a 2 x 2 grid of points, the paths shared among them.
constexpr int kJudgeGrid = 3;
constexpr int kSubpixels = 2;
// The second frame's exposure, in multiples of the bundle's: pixels white at the bundle's exposure are
// read from it (4 stops: only lamps and the hot spots beside them clip at the first).
constexpr double kBrightExposure = 16.0;
// A rendered channel at this code is clipped (brighter than white): unreadable.
constexpr std::uint8_t kClipped = 255;
// The error map's full colour: this relative error, red too bright, blue too dark (white at 0).
constexpr double kMapFullScale = 0.25;
// The error map colours each compared pixel by its block's error (shown over reference summed over the
// block's compared pixels): the reference's noise per pixel would hide a band a few pixels wide.
constexpr int kMapBlock = 4;

// A compared pixel's colour in the error map for relative error e (shown / reference - 1).
void paint_error(render::Image& map, int x, int y, double e) {
  const double t = std::clamp(std::abs(e) / kMapFullScale, 0.0, 1.0);
  const auto fade = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - t)));
  std::uint8_t* p = &map.rgba[(std::size_t(y) * map.width + x) * 4];
  p[0] = e > 0.0 ? 255 : fade;
  p[1] = fade;
  p[2] = e > 0.0 ? fade : 255;
}

enum class Seen : std::uint8_t { Surface, Nothing, Back, Lamp, Glass };

struct PixelHit {
  Seen seen = Seen::Nothing;
  std::uint32_t polygon = 0;
  bool mixed = false;  // its footprint meets more than this polygon's surface
};

class ViewRays {
 public:
  // Through the kiosk's own projection (render/camera.hpp), so the rays are the frame's, head-coupled
  // screens included.
  ViewRays(const render::View& view, int width, int height)
      : eye_(view.eye),
        width_(width),
        height_(height),
        unproject_(glm::inverse(render::view_projection_double(view, double(width) / double(height)))) {}
  // Direction through (x, y) in pixels from the top-left corner: towards that pixel's point on the near
  // plane.
  [[nodiscard]] model::Vec3 through(double x, double y) const {
    const glm::dvec4 near =
        unproject_ * glm::dvec4(2.0 * x / width_ - 1.0, 1.0 - 2.0 * y / height_, -1.0, 1.0);
    return glm::normalize(model::Vec3(near) / near.w - eye_);
  }
  [[nodiscard]] const model::Vec3& eye() const { return eye_; }

 private:
  model::Vec3 eye_;
  int width_, height_;
  glm::dmat4 unproject_;
};

struct Scene {
  const model::Bundle& bundle;
  std::unique_ptr<compiler::TriangleBvh> bvh;  // every drawn triangle, panels too; `polygon`: the bundle's
  explicit Scene(const model::Bundle& b) : bundle(b) {
    std::vector<compiler::Triangle> triangles;
    const auto v = b.vertices();
    for (const auto& c : compiler::drawn_triangles(b, true))
      triangles.push_back({compiler::vertex_position(v[c[0]]), compiler::vertex_position(v[c[1]]),
                           compiler::vertex_position(v[c[2]]), v[c[0]].polygon});
    bvh = std::make_unique<compiler::TriangleBvh>(std::move(triangles));
  }
  // What the ray from the eye meets first, and the surface point there (position, shown side, albedo).
  PixelHit meet(const model::Vec3& eye, const model::Vec3& dir,
                compiler::SurfacePoint* point = nullptr) const {
    const auto hit = bvh->closest_facing(eye, dir, 0.0, 1e30, 1e-6);
    if (!hit) return {};
    const std::uint32_t polygon = bvh->triangles()[hit->triangle].polygon;
    const auto role = static_cast<model::Role>(bundle.polygons()[polygon].role);
    if (role == model::Role::Luminaire) return {Seen::Lamp, polygon};
    if (role == model::Role::Glass) return {Seen::Glass, polygon};
    const auto& first = bundle.vertices()[bundle.polygons()[polygon].first_vertex];
    const model::Vec3 normal = glm::normalize(compiler::vertex_normal(first));
    if (glm::dot(normal, dir) >= 0.0) return {Seen::Back, polygon};
    if (point) *point = {eye + dir * hit->t, normal, {first.albedo[0], first.albedo[1], first.albedo[2]}};
    return {Seen::Surface, polygon};
  }
};

render::Image render_still(render::Renderer& renderer, const render::View& view, int width, int height,
                           int samples, std::optional<float> exposure) {
  renderer.set_exposure(exposure);
  render::RefineSettings settings;
  settings.aa_samples = samples;
  renderer.set_refine_settings(settings);
  while (renderer.refine(view, width, height)) {
  }
  return renderer.read_pixels(width, height);
}

// Linear luminance-weighted radiosity a pixel shows (W/m2), or nullopt if a channel clipped.
std::optional<double> shown(const render::Image& image, int x, int y, double exposure) {
  const auto& decode = model::srgb_decode_table();
  const std::uint8_t* p = image.pixel(x, y);
  if (p[0] == kClipped || p[1] == kClipped || p[2] == kClipped) return std::nullopt;
  return exposure * model::luminance_weight({decode[p[0]], decode[p[1]], decode[p[2]]});
}

int run(const Args& a) {
  const auto size = parse_frame_size(a.size, 8192);
  if (!size) throw Error("walk bench image: --size '" + a.size + "' is not WIDTHxHEIGHT (e.g. 320x240)");
  const auto [width, height] = *size;
  std::string path = a.input;
  const fs::path tmp = fs::temp_directory_path() / ("walk_bench_image_" + std::to_string(::getpid()));
  if (fs::path(a.input).extension() != ".walk") {
    fs::create_directories(tmp);
    path = (tmp / "scene.walk").string();
    model::write_bundle(path,
                        compiler::compile_scene(compiler::load_scene_config(a.input), {a.threads}).bundle);
  }
  const auto bundle = model::Bundle::open(path);
  if (!bundle->textures().empty())
    spdlog::warn("walk bench image: {} has albedo maps; the reference reads each surface's vertex albedo",
                 path);
  render::View view;
  view.eye = option_vec3(a.eye, "eye", "in local metres");
  view.forward = option_vec3(a.look, "look", "in local metres") - view.eye;
  view.fov_y_degrees = a.fov;
  const ViewRays rays(view, width, height);
  const Scene scene(*bundle);

  // Judge every pixel: what its footprint meets, and whether that is one polygon's surface.
  std::vector<PixelHit> judged(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      PixelHit pixel = scene.meet(rays.eye(), rays.through(x + 0.5, y + 0.5));
      for (int j = 0; j < kJudgeGrid * kJudgeGrid && pixel.seen == Seen::Surface && !pixel.mixed; ++j) {
        const PixelHit sub = scene.meet(rays.eye(), rays.through(x + (j % kJudgeGrid + 0.5) / kJudgeGrid,
                                                                 y + (j / kJudgeGrid + 0.5) / kJudgeGrid));
        pixel.mixed = sub.seen != Seen::Surface || sub.polygon != pixel.polygon;
      }
      judged[std::size_t(y) * width + x] = pixel;
    }
  std::array<std::size_t, 5> seen{};
  std::size_t silhouettes = 0;
  std::vector<std::size_t> eligible;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelHit& p = judged[std::size_t(y) * width + x];
      ++seen[std::size_t(p.seen)];
      if (p.seen != Seen::Surface) continue;
      // One pixel from an edge between polygons: the renderer's samples spread a little past the pixel.
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
          const PixelHit& n = judged[std::size_t(ny) * width + nx];
          edge |= n.seen != Seen::Surface || n.mixed || n.polygon != p.polygon;
        }
      if (edge) {
        ++silhouettes;
        continue;
      }
      eligible.push_back(std::size_t(y) * width + x);
    }
  std::mt19937_64 rng(0x5eed);
  std::shuffle(eligible.begin(), eligible.end(), rng);
  eligible.resize(std::min(eligible.size(), std::size_t(a.pixels)));
  std::sort(eligible.begin(), eligible.end());
  if (eligible.empty())
    throw Error("walk bench image: no pixel of the view shows one surface; check --eye/--look");

  // The frame as a still kiosk shows it, at the bundle's exposure and 4 stops darker.
  render::BackendOptions options;
  options.kind = render::parse_backend_kind(a.backend);
  options.width = width;
  options.height = height;
  auto backend = render::Backend::create(options);
  backend->make_current();
  render::Renderer renderer(*bundle);
  const auto render_start = std::chrono::steady_clock::now();
  const double exposure = bundle->meta().exposure;
  const render::Image frame = render_still(renderer, view, width, height, a.samples, std::nullopt);
  const render::Image darker =
      render_still(renderer, view, width, height, a.samples, float(exposure * kBrightExposure));
  const double render_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
  if (!a.frame.empty()) render::write_png(a.frame, frame);

  // The reference at each compared pixel's 2 x 2 points.
  std::vector<compiler::SurfacePoint> points;
  for (const std::size_t i : eligible) {
    const int x = int(i % width), y = int(i / width);
    for (int j = 0; j < kSubpixels * kSubpixels; ++j) {
      compiler::SurfacePoint p;
      scene.meet(
          rays.eye(),
          rays.through(x + (j % kSubpixels + 0.5) / kSubpixels, y + (j / kSubpixels + 0.5) / kSubpixels), &p);
      points.push_back(p);
    }
  }
  const compiler::PathTracer tracer(*bundle);
  const int per_point = std::max(1, a.reference_paths / (kSubpixels * kSubpixels));
  const compiler::PathReference ref = tracer.trace(points, per_point, 1, a.threads);

  // Relative RMS error per pixel, the reference's noise taken out in quadrature; the floor 8-bit display
  // codes alone would leave; the ratio of the means. Ambient light (a display-time constant standing in for
  // what the scene leaves out) is taken off the shown pixel: the reference has none.
  double difference = 0.0, scale = 0.0, noise = 0.0, quantisation = 0.0, sum_shown = 0.0, sum_ref = 0.0;
  std::size_t compared = 0, clipped = 0;
  const int blocks_x = (width + kMapBlock - 1) / kMapBlock;
  std::vector<double> block_shown(std::size_t(blocks_x) * ((height + kMapBlock - 1) / kMapBlock), 0.0),
      block_reference(block_shown.size(), 0.0);
  std::vector<std::size_t> painted;  // the compared pixels
  for (std::size_t k = 0; k < eligible.size(); ++k) {
    const int x = int(eligible[k] % width), y = int(eligible[k] / width);
    double reference = 0.0, variance = 0.0;
    double ambient = 0.0;
    for (int j = 0; j < kSubpixels * kSubpixels; ++j) {
      const std::size_t q = k * kSubpixels * kSubpixels + j;
      reference += model::luminance_weight(ref.radiosity[q]) / (kSubpixels * kSubpixels);
      variance += ref.standard_error[q] * ref.standard_error[q] / std::pow(kSubpixels * kSubpixels, 2);
      ambient +=
          bundle->meta().ambient * model::luminance_weight(points[q].albedo) / (kSubpixels * kSubpixels);
    }
    std::optional<double> value = shown(frame, x, y, exposure);
    double at = exposure;
    if (!value) {
      at = exposure * kBrightExposure;
      value = shown(darker, x, y, at);
    }
    if (!value) {
      ++clipped;
      continue;
    }
    const double light = *value - ambient;
    const std::size_t block = std::size_t(y / kMapBlock) * blocks_x + x / kMapBlock;
    block_shown[block] += light;
    block_reference[block] += reference;
    painted.push_back(eligible[k]);
    difference += (light - reference) * (light - reference);
    scale += reference * reference;
    noise += variance;
    // What the reference itself would show through 8-bit codes at the same exposure.
    const double code = model::srgb_decode_table()[model::srgb_encode_byte(reference / at)] * at;
    quantisation += (code - reference) * (code - reference);
    sum_shown += light;
    sum_ref += reference;
    ++compared;
  }
  fs::remove_all(tmp);
  if (!a.error_map.empty()) {
    render::Image map = frame;  // the frame at a third of its brightness under the compared pixels' errors
    for (std::size_t i = 0; i < map.rgba.size(); ++i)
      if (i % 4 != 3) map.rgba[i] = static_cast<std::uint8_t>(map.rgba[i] / 3);
    for (const std::size_t i : painted) {
      const int x = int(i % width), y = int(i / width);
      const std::size_t block = std::size_t(y / kMapBlock) * blocks_x + x / kMapBlock;
      if (block_reference[block] > 0.0)
        paint_error(map, x, y, block_shown[block] / block_reference[block] - 1.0);
    }
    render::write_png(a.error_map, map);
  }
  if (!(scale > 0.0)) throw Error("walk bench image: the compared pixels are dark in the reference");
  std::printf(
      "view,width,height,aa_samples,pixels,surface,lamp,glass,nothing_or_back,silhouette,clipped,"
      "error_vs_reference,reference_noise,quantisation,mean_ratio,render_seconds,reference_seconds\n");
  std::printf("%s,%d,%d,%d,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%.5f,%.5f,%.5f,%.4f,%.3f,%.3f\n",
              fs::path(a.input).stem().string().c_str(), width, height, a.samples, compared,
              seen[std::size_t(Seen::Surface)], seen[std::size_t(Seen::Lamp)], seen[std::size_t(Seen::Glass)],
              seen[std::size_t(Seen::Nothing)] + seen[std::size_t(Seen::Back)], silhouettes, clipped,
              std::sqrt(std::max(0.0, difference - noise) / scale), std::sqrt(noise / scale),
              std::sqrt(quantisation / scale), sum_shown / sum_ref, render_seconds, ref.seconds);
  return 0;
}

}  // namespace bench_image_command

void add_bench_image_command(CLI::App& bench, int& exit_code) {
  using namespace bench_image_command;
  auto args = std::make_shared<Args>();
  auto* cmd = bench.add_subcommand(
      "image",
      "A still frame's light, pixel by pixel, against a path-traced reference of the same view (CSV)");
  cmd->add_option("input", args->input, "A .walk bundle, or a scene config compiled at its own settings")
      ->required();
  cmd->add_option("--eye", args->eye, "Eye position x,y,z (local metres)")->delimiter(',')->required();
  cmd->add_option("--look", args->look, "Point looked at x,y,z (local metres)")->delimiter(',')->required();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT");
  cmd->add_option("--fov", args->fov, "Vertical field of view, degrees");
  cmd->add_option("--samples", args->samples, "Anti-aliasing samples of the still frame")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--pixels", args->pixels,
                  "Pixels compared (drawn at random among those showing one surface)")
      ->check(CLI::Range(1, 10000000));
  cmd->add_option("--reference-paths", args->reference_paths, "Reference paths per pixel")
      ->check(CLI::Range(4, 100000000));
  cmd->add_option("--backend", args->backend, "auto, osmesa, egl, glfw or gbm");
  cmd->add_option("-j,--threads", args->threads, "Worker threads");
  cmd->add_option("--frame", args->frame, "Also write the rendered frame (PNG)");
  cmd->add_option(
      "--error-map", args->error_map,
      "Also write the compared pixels' error by 4 x 4 blocks (PNG: red too bright, blue too dark, full at "
      "25 %)");
  cmd->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace walk::tools
