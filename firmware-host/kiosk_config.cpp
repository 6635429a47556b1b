#include "firmware-host/kiosk_config.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <numbers>

#include "firmware-host/device_config.hpp"
#include "firmware-host/toml_section.hpp"
#include "model/error.hpp"

namespace walk::kiosk {
namespace {

namespace fs = std::filesystem;

constexpr double kDegrees = std::numbers::pi / 180.0;

std::string resolve(const std::string& base_dir, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute()) return p;
  return (fs::path(base_dir) / p).lexically_normal().string();
}

StartConfig read_start(const Section& start) {
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
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw Error(located(path, e.source().begin.line, std::string(e.description())));
  }
  const std::string dir = fs::path(path).parent_path().string();
  const Section top(root, path, "");
  top.only(
      {"bundle", "buildings", "display", "start", "walker", "devices", "dimmers", "simulation", "output"});

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
      const Section b(*t, path, "buildings[" + std::to_string(i) + "]");
      b.only({"bundle", "start"});
      const auto file = b.string("bundle");
      if (!file) b.fail("", "missing key 'bundle'");
      const auto st = b.table("start");
      if (!st) b.fail("", "missing table 'start' (x, y and floor_z or eye_z in that building)");
      c.buildings.push_back({resolve(dir, *file), read_start(*st)});
    }
  }

  if (auto s = top.table("display")) {
    s->only({"backend", "width", "height", "fullscreen", "monitor", "drm_device", "fov_y_deg", "refine",
             "target_hz"});
    c.display.backend = s->string("backend").value_or(c.display.backend);
    if (c.display.backend != "auto" && c.display.backend != "osmesa" && c.display.backend != "egl" &&
        c.display.backend != "glfw" && c.display.backend != "gbm")
      s->fail("backend", "unknown backend '" + c.display.backend + "' (auto, osmesa, egl, glfw or gbm)");
    c.display.monitor = s->integer("monitor", c.display.monitor, 0, 63);
    c.display.drm_device = s->string("drm_device").value_or(c.display.drm_device);
    c.display.refine = s->boolean("refine", c.display.refine);
    c.display.target_hz = s->number("target_hz", c.display.target_hz, 1.0, 480.0);
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
    c.dimmer_circuits = s->strings("channels");
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
