#include "firmware-host/kiosk_config.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <numbers>

#include "model/error.hpp"

namespace walk::kiosk {
namespace {

namespace fs = std::filesystem;

// A table plus its dotted path, so every error can say "file:line: display.width: ...".
class Section {
 public:
  Section(const toml::table& table, const std::string& file, std::string prefix)
      : table_(table), file_(file), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = key.empty() ? nullptr : table_.get(key);
    const auto line = n ? n->source().begin.line : table_.source().begin.line;
    throw Error(located(file_, line, (key.empty() ? prefix_ : path(key)) + ": " + what));
  }
  [[nodiscard]] std::string path(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }

  void only(std::initializer_list<const char*> known) const {
    for (const auto& [k, v] : table_) {
      bool ok = false;
      for (const char* name : known) ok = ok || k.str() == name;
      if (!ok) fail(std::string(k.str()), "unknown key");
    }
  }
  std::optional<double> number(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) return *v;
    fail(key, "expected a number");
  }
  double number(const std::string& key, double fallback, double lo, double hi) const {
    const double v = number(key).value_or(fallback);
    if (!(v >= lo && v <= hi)) fail(key, "must be between " + fmt(lo) + " and " + fmt(hi));
    return v;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) const {
    const toml::node* n = table_.get(key);
    if (!n) return fallback;
    if (!n->is_integer()) fail(key, "expected an integer");
    const auto v = *n->value<long long>();
    if (v < lo || v > hi) fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return static_cast<int>(v);
  }
  bool boolean(const std::string& key, bool fallback) const {
    const toml::node* n = table_.get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "expected true or false");
    return *n->value<bool>();
  }
  std::optional<std::string> string(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "expected a string");
    return *n->value<std::string>();
  }
  std::vector<std::string> strings(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return {};
    const auto* arr = n->as_array();
    if (!arr) fail(key, "expected an array of strings");
    std::vector<std::string> out;
    for (const auto& item : *arr) {
      if (!item.is_string()) fail(key, "expected an array of strings");
      out.push_back(*item.value<std::string>());
    }
    return out;
  }
  std::optional<Section> table(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_table()) fail(key, "expected a table");
    return Section(*n->as_table(), file_, path(key));
  }

 private:
  static std::string fmt(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }
  const toml::table& table_;
  const std::string& file_;
  std::string prefix_;
};

constexpr double kDegrees = std::numbers::pi / 180.0;

std::string resolve(const std::string& base_dir, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute()) return p;
  return (fs::path(base_dir) / p).lexically_normal().string();
}

DeviceConfig device(const Section& s, const std::string& dir) {
  s.only({"backend", "trace"});
  DeviceConfig d;
  d.backend = s.string("backend").value_or("mock");
  if (d.backend != "mock") s.fail("backend", "unknown device backend '" + d.backend + "' (known: mock)");
  const auto trace = s.string("trace");
  if (!trace) s.fail("", "missing key 'trace' (the CSV file a mock device replays)");
  d.trace = resolve(dir, *trace);
  return d;
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
  top.only({"bundle", "display", "start", "walker", "devices", "dimmers", "simulation", "output"});

  KioskConfig c;
  c.path = path;
  const auto bundle = top.string("bundle");
  if (!bundle) top.fail("", "missing key 'bundle' (path of the compiled .walk file)");
  c.bundle = resolve(dir, *bundle);

  if (auto s = top.table("display")) {
    s->only({"backend", "width", "height", "fullscreen", "fov_y_deg"});
    c.display.backend = s->string("backend").value_or(c.display.backend);
    if (c.display.backend != "auto" && c.display.backend != "osmesa" && c.display.backend != "egl" &&
        c.display.backend != "glfw")
      s->fail("backend", "unknown backend '" + c.display.backend + "' (auto, osmesa, egl or glfw)");
    c.display.width = s->integer("width", c.display.width, 16, 16384);
    c.display.height = s->integer("height", c.display.height, 16, 16384);
    c.display.fullscreen = s->boolean("fullscreen", c.display.fullscreen);
    c.display.fov_y_degrees = s->number("fov_y_deg", c.display.fov_y_degrees, 10.0, 150.0);
  }

  const auto start = top.table("start");
  if (!start) top.fail("", "missing table [start] (x, y and floor_z or eye_z of the walker)");
  start->only({"x", "y", "floor_z", "eye_z", "heading_deg"});
  const auto x = start->number("x"), y = start->number("y");
  if (!x) start->fail("", "missing key 'x'");
  if (!y) start->fail("", "missing key 'y'");
  c.start.x = *x;
  c.start.y = *y;
  c.start.floor_z = start->number("floor_z");
  c.start.eye_z = start->number("eye_z");
  if (c.start.floor_z && c.start.eye_z) start->fail("eye_z", "give floor_z or eye_z, not both");
  c.start.heading = start->number("heading_deg", 0.0, -360.0, 360.0) * kDegrees;

  if (auto s = top.table("walker")) {
    s->only({"eye_height", "step_height", "head_clearance"});
    c.walker.eye_height = s->number("eye_height", c.walker.eye_height, 0.5, 2.5);
    c.walker.step_height = s->number("step_height", c.walker.step_height, 0.0, 1.0);
    c.walker.head_clearance = s->number("head_clearance", c.walker.head_clearance, 0.0, 1.0);
    if (c.walker.step_height >= c.walker.eye_height) s->fail("step_height", "must be below eye_height");
  }

  if (auto s = top.table("devices")) {
    s->only({"treadmill", "head_tracker", "dimmer_panel"});
    if (auto d = s->table("treadmill")) c.devices.treadmill = device(*d, dir);
    if (auto d = s->table("head_tracker")) c.devices.head_tracker = device(*d, dir);
    if (auto d = s->table("dimmer_panel")) c.devices.dimmer_panel = device(*d, dir);
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
