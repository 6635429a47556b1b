#include "firmware-host/kiosk_config.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <numbers>

#include "firmware-host/device_config.hpp"
#include "model/error.hpp"
#include "model/toml_table.hpp"
#include "render/frame_timing.hpp"

namespace walk::kiosk {
namespace {

namespace fs = std::filesystem;

constexpr double kDegrees = std::numbers::pi / 180.0;

std::string resolve(const std::string& base_dir, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute()) return p;
  return (fs::path(base_dir) / p).lexically_normal().string();
}

// Corners measured with a tape: an upper_right this far (metres) from the rectangle's fourth corner is a
// mistake in the numbers, not measuring error.
constexpr double kCornerTolerance = 0.01;
// The nominal eye must be at least this far in front of the screen (metres), or the view is degenerate.
constexpr double kMinEyeToScreen = 0.05;
// [display] white_luminance, cd/m2: from a dim night scene to daylit interiors.
constexpr double kMinWhiteLuminance = 1.0;
constexpr double kMaxWhiteLuminance = 100000.0;

glm::dvec3 point(const TomlTable& s, const std::string& key) {
  const toml::node* n = s.raw().get(key);
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a || a->size() != 3)
    s.fail(key, "expected [x, y, z] in metres (tracker frame: x right, y forward, z up)");
  glm::dvec3 p(0.0);
  for (int i = 0; i < 3; ++i) {
    const auto v = (*a)[std::size_t(i)].value<double>();
    if (!v || !std::isfinite(*v) || std::abs(*v) > 100.0)
      s.fail(key, "expected three numbers within 100 m of the tracker's origin");
    p[i] = *v;
  }
  return p;
}

ScreenCorners read_screen(const TomlTable& s) {
  s.only({"lower_left", "lower_right", "upper_left", "upper_right"});
  for (const char* key : {"lower_left", "lower_right", "upper_left"})
    if (!s.raw().get(key))
      s.fail("", std::string("missing key '") + key + "' (three corners define the screen)");
  ScreenCorners c{point(s, "lower_left"), point(s, "lower_right"), point(s, "upper_left")};
  const glm::dvec3 across = c.lower_right - c.lower_left, up = c.upper_left - c.lower_left;
  const double w = glm::length(across), h = glm::length(up);
  if (w < kCornerTolerance || h < kCornerTolerance)
    s.fail("", "corners coincide: the screen has no width or height");
  if (std::abs(glm::dot(across, up)) > 0.01 * w * h)
    s.fail("upper_left",
           "corners do not form a rectangle: lower_left->lower_right and lower_left->upper_left "
           "must be at right angles");
  if (s.raw().get("upper_right")) {
    const glm::dvec3 expected = c.lower_right + up;
    if (glm::length(point(s, "upper_right") - expected) > kCornerTolerance)
      s.fail("upper_right",
             "is not where the other three corners put it: the corners do not form a rectangle");
  }
  return c;
}

SteeringConfig read_steering(const TomlTable& s) {
  s.only({"head_turn", "dead_zone_deg", "turn_gain", "max_turn_deg_s", "ease_seconds"});
  SteeringConfig c;
  c.head_turn = s.boolean("head_turn", c.head_turn);
  c.dead_zone = s.number("dead_zone_deg", c.dead_zone / kDegrees, 0.0, 90.0) * kDegrees;
  c.turn_gain = s.number("turn_gain", c.turn_gain, 0.0, 10.0);
  c.max_turn_rate = s.number("max_turn_deg_s", c.max_turn_rate / kDegrees, 1.0, 360.0) * kDegrees;
  c.ease_seconds = s.number("ease_seconds", c.ease_seconds, 0.0, 10.0);
  return c;
}

StartConfig read_start(const TomlTable& start) {
  start.only({"x", "y", "floor_z", "eye_z", "heading_deg"});
  const auto x = start.number("x"), y = start.number("y");
  if (!x) start.fail("", "missing key 'x'");
  if (!y) start.fail("", "missing key 'y'");
  StartConfig c;
  c.x = *x;
  c.y = *y;
  c.floor_z = start.number("floor_z");
  c.eye_z = start.number("eye_z");
  if (c.floor_z && c.eye_z) start.fail("eye_z", "give floor_z or eye_z, not both");
  c.heading = start.number("heading_deg", 0.0, -360.0, 360.0) * kDegrees;
  return c;
}

}  // namespace

KioskConfig load_kiosk_config(const std::string& path) {
  if (!fs::exists(path)) throw Error(located(path, 0, "kiosk config not found"));
  const toml::table root = parse_toml_file(path);
  const std::string dir = fs::path(path).parent_path().string();
  const TomlTable top(root, path, "");
  top.only({"bundle", "buildings", "display", "start", "walker", "steering", "devices", "dimmers",
            "simulation", "output"});

  KioskConfig c;
  c.path = path;
  const auto bundle = top.string("bundle");
  if (!bundle) top.fail("", "missing key 'bundle' (path of the compiled .walk file)");
  c.bundle = resolve(dir, *bundle);

  if (const toml::node* n = root.get("buildings")) {
    const toml::array* arr = n->as_array();
    if (!arr) top.fail("buildings", "expected [[buildings]] tables, each with bundle and [start]");
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table* t = arr->get(i)->as_table();
      if (!t) top.fail("buildings", "expected [[buildings]] tables, each with bundle and [start]");
      const TomlTable b(*t, path, "buildings[" + std::to_string(i) + "]");
      b.only({"bundle", "start"});
      const auto file = b.string("bundle");
      if (!file) b.fail("", "missing key 'bundle'");
      const auto st = b.table("start");
      if (!st) b.fail("", "missing table 'start' (x, y and floor_z or eye_z in that building)");
      c.buildings.push_back({resolve(dir, *file), read_start(*st)});
    }
  }

  if (auto s = top.table("display")) {
    s->only({"mode",           "screen",      "screens",       "outputs",         "stereo",
             "eye_separation", "nominal_eye", "tracking_ease", "backend",         "width",
             "height",         "fullscreen",  "monitor",       "drm_device",      "fov_y_deg",
             "refine",         "target_hz",   "frame_timing",  "white_luminance", "light_form"});
    c.display.mode = s->string("mode").value_or(c.display.mode);
    if (c.display.mode != "screen" && c.display.mode != "hmd")
      s->fail("mode",
              "unknown mode '" + c.display.mode + "' (screen: a fixed display; hmd: a head-mounted one)");
    if (auto t = s->table("screen")) c.display.screen = read_screen(*t);
    if (const toml::node* n = s->raw().get("screens")) {
      const toml::array* arr = n->as_array();
      if (!arr || arr->empty()) s->fail("screens", "expected [[display.screens]] tables, each with corners");
      if (c.display.screen)
        s->fail("screens", "give either [display.screen] or [[display.screens]], not both");
      for (std::size_t i = 0; i < arr->size(); ++i) {
        const toml::table* t = arr->get(i)->as_table();
        if (!t) s->fail("screens", "expected [[display.screens]] tables, each with corners");
        c.display.screens.push_back(
            read_screen(TomlTable(*t, path, "display.screens[" + std::to_string(i) + "]")));
      }
      if (c.display.screens.size() > 8) s->fail("screens", "at most 8 screens");
    }
    c.display.outputs = s->string("outputs").value_or(c.display.outputs);
    if (c.display.outputs != "span" && c.display.outputs != "monitors")
      s->fail("outputs", "unknown outputs '" + c.display.outputs + "' (span or monitors)");
    c.display.stereo = s->string("stereo").value_or(c.display.stereo);
    if (c.display.stereo != "off" && c.display.stereo != "side_by_side" && c.display.stereo != "quad_buffer")
      s->fail("stereo", "unknown stereo '" + c.display.stereo + "' (off, side_by_side or quad_buffer)");
    c.display.eye_separation = s->number("eye_separation", c.display.eye_separation, 0.0, 0.2);
    if (s->raw().get("nominal_eye")) c.display.nominal_eye = point(*s, "nominal_eye");
    c.display.tracking_ease = s->number("tracking_ease", c.display.tracking_ease, 0.0, 10.0);
    c.display.backend = s->string("backend").value_or(c.display.backend);
    if (c.display.backend != "auto" && c.display.backend != "osmesa" && c.display.backend != "egl" &&
        c.display.backend != "glfw" && c.display.backend != "gbm")
      s->fail("backend", "unknown backend '" + c.display.backend + "' (auto, osmesa, egl, glfw or gbm)");
    c.display.monitor = s->integer("monitor", c.display.monitor, 0, 63);
    // GBM scans out through one DRM master per device: one connector per walkd, so several outputs need
    // GLFW's windows (each its own context) for now.
    if (c.display.outputs == "monitors" && c.display.backend == "gbm")
      s->fail("outputs",
              "\"monitors\" needs backend = \"glfw\" (one GBM connector per walkd); or use "
              "outputs = \"span\" with one output across the screens");
    c.display.drm_device = s->string("drm_device").value_or(c.display.drm_device);
    c.display.refine = s->boolean("refine", c.display.refine);
    c.display.target_hz = s->number("target_hz", c.display.target_hz, 1.0, 480.0);
    if (s->has("white_luminance"))
      c.display.white_luminance = s->number("white_luminance", 100.0, kMinWhiteLuminance, kMaxWhiteLuminance);
    c.display.light_form = s->string("light_form").value_or(c.display.light_form);
    if (c.display.light_form != "compiled" && c.display.light_form != "full")
      s->fail("light_form",
              "unknown light form '" + c.display.light_form +
                  "' (compiled: compact where the compiler found it good; full: every circuit in full)");
    c.display.frame_timing = s->string("frame_timing").value_or(c.display.frame_timing);
    if (!render::parse_frame_timing(c.display.frame_timing))
      s->fail("frame_timing", "unknown frame timing '" + c.display.frame_timing + "' (" +
                                  std::string(render::kFrameTimingNames) + ")");
    c.display.width = s->integer("width", c.display.width, 16, 16384);
    c.display.height = s->integer("height", c.display.height, 16, 16384);
    c.display.fullscreen = s->boolean("fullscreen", c.display.fullscreen);
    c.display.fov_y_degrees = s->number("fov_y_deg", c.display.fov_y_degrees, 10.0, 150.0);
  }

  const auto start = top.table("start");
  if (!start) top.fail("", "missing table [start] (x, y and floor_z or eye_z of the walker)");
  c.start = read_start(*start);

  if (auto s = top.table("walker")) {
    s->only({"eye_height", "step_height", "head_clearance"});
    c.walker.eye_height = s->number("eye_height", c.walker.eye_height, 0.5, 2.5);
    c.walker.step_height = s->number("step_height", c.walker.step_height, 0.0, 1.0);
    c.walker.head_clearance = s->number("head_clearance", c.walker.head_clearance, 0.0, 1.0);
    if (c.walker.step_height >= c.walker.eye_height) s->fail("step_height", "must be below eye_height");
  }

  if (auto s = top.table("steering")) c.steering = read_steering(*s);
  if (c.display.mode == "screen") {
    // The eye at rest must look at each screen's front: its normal (right x up) points at the viewer.
    std::vector<std::pair<ScreenCorners, std::string>> screens;
    if (c.display.screen) screens.emplace_back(*c.display.screen, "screen");
    for (std::size_t i = 0; i < c.display.screens.size(); ++i)
      screens.emplace_back(c.display.screens[i], "screens[" + std::to_string(i) + "]");
    for (const auto& [sc, key] : screens) {
      const glm::dvec3 normal =
          glm::normalize(glm::cross(sc.lower_right - sc.lower_left, sc.upper_left - sc.lower_left));
      const glm::dvec3 eye = c.display.nominal_eye.value_or(glm::dvec3(0.0, 0.0, c.walker.eye_height));
      if (glm::dot(eye - sc.lower_left, normal) < kMinEyeToScreen)
        top.table("display")->fail(key,
                                   "the nominal eye is not in front of the screen (give the corners as "
                                   "seen from the walker: lower_left on the left)");
    }
  }

  if (auto s = top.table("devices")) {
    s->only({"treadmill", "head_tracker", "dimmer_panel", "buttons"});
    if (auto d = s->table("treadmill")) c.devices.treadmill = read_device(*d, DeviceRole::Treadmill, dir);
    if (auto d = s->table("head_tracker"))
      c.devices.head_tracker = read_device(*d, DeviceRole::HeadTracker, dir);
    if (auto d = s->table("dimmer_panel"))
      c.devices.dimmer_panel = read_device(*d, DeviceRole::DimmerPanel, dir);
    if (auto d = s->table("buttons")) c.devices.buttons = read_device(*d, DeviceRole::Buttons, dir);
  }

  if (auto s = top.table("dimmers")) {
    s->only({"channels"});
    c.dimmer_circuits = s->strings("channels").value_or(std::vector<std::string>{});
  }

  if (auto s = top.table("simulation")) {
    s->only({"frame_rate", "seconds"});
    c.simulation.frame_rate = s->number("frame_rate", c.simulation.frame_rate, 1.0, 1000.0);
    c.simulation.seconds = s->number("seconds", c.simulation.seconds, 0.0, 1e6);
  }

  if (auto s = top.table("output")) {
    s->only({"folder", "png_every"});
    if (auto f = s->string("folder")) c.output.folder = resolve(dir, *f);
    c.output.png_every = s->number("png_every", c.output.png_every, 0.0, 1e6);
  }
  return c;
}

}  // namespace walk::kiosk
