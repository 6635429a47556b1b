#pragma once
// The kiosk's TOML config: which bundle, which display, where the walker starts, which devices, how dimmer
// channels map to circuits, simulation and output settings. Angles are degrees in the file, radians here;
// relative paths are resolved against the config file's folder. Errors name the file, line and key.
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "devices/gpio/gpio_device.hpp"
#include "devices/hid/hid_device.hpp"
#include "devices/modbus/modbus_panel.hpp"

namespace walk::kiosk {

// A physical screen's corners in the tracker frame (metres; see firmware-host/head_coupling.hpp).
struct ScreenCorners {
  glm::dvec3 lower_left{0.0}, lower_right{0.0}, upper_left{0.0};
};

struct DisplayConfig {
  // screen: a fixed display seen as a window from the tracked eye; hmd: the view turns with the head.
  std::string mode = "screen";
  std::optional<ScreenCorners> screen;  // none: a nominal screen spanning fov_y_degrees (head_coupling)
  // Several screens of one spanning output (e.g. three walls): each its own corners, side by side in the
  // output in this order, all drawn from the same eye. Exclusive with `screen`.
  std::vector<ScreenCorners> screens;
  // span: all screens side by side in one output; monitors: screen i on its own output, monitor + i
  // (GLFW windows, full screen with `fullscreen`).
  std::string outputs = "span";
  std::string stereo = "off";     // off | side_by_side | quad_buffer
  double eye_separation = 0.064;  // metres between the eyes (an adult's average interpupillary distance)
  std::optional<glm::dvec3> nominal_eye;  // tracker frame; none: (0, 0, walker eye height)
  double tracking_ease = 0.5;             // seconds to glide to or from the nominal eye
  std::string backend = "auto";           // auto | osmesa | egl | glfw | gbm
  int width = 1280;
  int height = 720;
  bool fullscreen = false;
  int monitor = 0;         // GLFW full screen and GBM: which connected display
  std::string drm_device;  // GBM only: e.g. /dev/dri/card1; empty: the first card
  double fov_y_degrees = 60.0;
  // Adaptive refinement (the paper's): coarse while moving at the level the governor picks for target_hz,
  // patches, diagonals, subdivision and anti-aliasing while still, and nothing drawn once converged.
  // false: every frame at full quality (for comparison).
  bool refine = true;
  double target_hz = 60.0;
  // How the governor times frames: auto (GL timer queries on hardware GPUs, glFinish on software
  // rasterizers), finish or queries (render/gpu_timer.hpp).
  std::string frame_timing = "auto";
  // A white diffuse surface this bright (cd/m2) is shown as white, instead of the bundle's exposure.
  std::optional<double> white_luminance;
  // "compiled": each circuit in the form the compiler chose (compact where within its limit); "full": every
  // circuit from the full float light (more display memory, no compact error).
  std::string light_form = "compiled";
};

struct StartConfig {
  double x = 0.0, y = 0.0;        // world metres
  std::optional<double> floor_z;  // world z of the floor to stand on ...
  std::optional<double> eye_z;    // ... or of the eye (floor = eye - eye height); neither: highest floor
  double heading = 0.0;           // radians, 0 = +x, counter-clockwise
};

// Walking direction in screen mode: the treadmill's steering, plus head yaw as a turn rate when head_turn.
struct SteeringConfig {
  bool head_turn = false;
  double dead_zone = 0.26;      // radians of yaw that do not turn (about 15 degrees: glances)
  double turn_gain = 1.0;       // radians per second of turn per radian of yaw beyond the dead zone
  double max_turn_rate = 0.79;  // radians per second (about 45 degrees per second)
  double ease_seconds = 0.4;    // time constant of the turn rate's easing
};

struct WalkerConfig {
  double eye_height = 1.6;  // above the floor
  double step_height = 0.35;
  double head_clearance = 0.2;  // collision band reaches eye height + this
};

struct DeviceConfig {
  DeviceConfig(std::string backend_ = {}, std::string trace_ = {})
      : backend(std::move(backend_)), trace(std::move(trace_)) {}
  std::string backend;  // mock (replay `trace`) | hid | gpio | modbus
  std::string trace;    // mock: resolved path
  devices::HidDeviceConfig hid;
  devices::GpioEncoderConfig encoder;
  devices::GpioButtonsConfig buttons;
  devices::ModbusPanelConfig modbus;
  int line = 0;  // config file line of the device's table, for errors about the device
};

struct DevicesConfig {
  std::optional<DeviceConfig> treadmill, head_tracker, dimmer_panel, buttons;
};

// Another building the next_building button switches to, with its own start.
struct BuildingConfig {
  std::string bundle;
  StartConfig start;
};

struct SimulationConfig {
  double frame_rate = 30.0;  // simulated frames per second (fixed step); also the real-time frame cap
  double seconds = 0.0;      // > 0: run a simulated clock for this long; 0: real time until stopped
};

struct OutputConfig {
  std::string folder = "walkd-out";  // summary.json and saved frames
  double png_every = 0.0;            // seconds of (simulated) time between saved frames; 0: never
};

struct KioskConfig {
  std::string path;                       // the config file itself
  std::string bundle;                     // resolved path of the .walk bundle
  std::vector<BuildingConfig> buildings;  // [[buildings]]: visited in order by next_building, then back
  DisplayConfig display;
  StartConfig start;
  WalkerConfig walker;
  SteeringConfig steering;
  DevicesConfig devices;
  std::vector<std::string> dimmer_circuits;  // channel i drives the circuit named dimmer_circuits[i]
  SimulationConfig simulation;
  OutputConfig output;
};

// Throws walk::Error "file:line: key: problem" for a missing file, bad syntax, a wrong type, an
// out-of-range value or an unknown key.
[[nodiscard]] KioskConfig load_kiosk_config(const std::string& path);

}  // namespace walk::kiosk
