#include "firmware-host/daemon.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <thread>

#include "model/error.hpp"

namespace walk::kiosk {
namespace {

constexpr double kMaxRealtimeStep = 0.25;  // after a stall, do not teleport the walker through walls
constexpr double kHugeZ = 1e9;

NavSettings nav_settings(const WalkerConfig& w) {
  NavSettings s;
  s.step_height = w.step_height;
  s.head_height = w.eye_height + w.head_clearance;
  return s;
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Daemon::Daemon(const KioskConfig& config, const model::Bundle& bundle, FrameRenderer& renderer,
               DeviceSet devices)
    : config_(config),
      bundle_(bundle),
      renderer_(renderer),
      devices_(std::move(devices)),
      origin_(bundle.meta().origin[0], bundle.meta().origin[1], bundle.meta().origin[2]),
      navigator_({bundle.vertices(), bundle.indices(), bundle.polygons()}, nav_settings(config.walker)) {
  // Start: world coordinates from the config, local inside.
  double z = kHugeZ;
  if (config.start.floor_z) z = *config.start.floor_z - origin_.z;
  if (config.start.eye_z) z = *config.start.eye_z - config.walker.eye_height - origin_.z;
  start_ = {config.start.x - origin_.x, config.start.y - origin_.y, z};
  if (!navigator_.place(start_))
    throw Error(
        located(config.path, 0,
                fmt::format("start: no floor at world ({:g}, {:g}) within step height below the given z, "
                            "or the walker's body overlaps a wall there",
                            config.start.x, config.start.y),
                "move [start] into a room of the bundle"));
  heading_ = config.start.heading;

  levels_.resize(bundle.circuits().size());
  for (std::size_t i = 0; i < levels_.size(); ++i) levels_[i] = bundle.circuits()[i].default_level;
  channel_circuit_ = map_channels(config_, devices_);
}

std::vector<std::uint32_t> Daemon::map_channels(const KioskConfig& config, const DeviceSet& devices) const {
  std::vector<std::uint32_t> out;
  for (std::size_t ch = 0; ch < config.dimmer_circuits.size(); ++ch) {
    const auto& name = config.dimmer_circuits[ch];
    std::uint32_t found = 0xffffffffu;
    for (std::uint32_t c = 0; c < bundle_.circuits().size(); ++c)
      if (bundle_.string(bundle_.circuits()[c].name) == name) found = c;
    if (found == 0xffffffffu)
      throw Error(located(config.path, 0,
                          fmt::format("dimmers.channels[{}]: the bundle has no circuit named '{}'", ch, name),
                          "walk inspect lists the circuits"));
    out.push_back(found);
  }
  if (devices.dimmer_panel && devices.dimmer_panel->channel_count() < out.size())
    throw Error(located(config.path, 0,
                        fmt::format("dimmers.channels maps {} channels but the dimmer panel has {}",
                                    out.size(), devices.dimmer_panel->channel_count())));
  return out;
}

std::string Daemon::room_name() const {
  if (!group_ || *group_ >= bundle_.groups().size()) return "";
  return std::string(bundle_.string(bundle_.groups()[*group_].name));
}

void Daemon::track_visits() {
  const glm::dvec3 eye = navigator_.feet() + glm::dvec3(0, 0, config_.walker.eye_height);
  const double p[3] = {eye.x, eye.y, eye.z};
  cell_ = bundle_.locate_cell(p);
  auto& cells = summary_.cells_visited;
  if (std::find(cells.begin(), cells.end(), cell_) == cells.end()) cells.push_back(cell_);

  const auto poly = navigator_.floor_polygon();
  const std::optional<std::uint32_t> group =
      poly < bundle_.polygons().size() ? std::optional(bundle_.polygons()[poly].group) : std::nullopt;
  if (group == group_) return;
  const std::string from = room_name();
  group_ = group;
  const std::string to = room_name();
  const glm::dvec3 w = to_world(navigator_.feet());
  if (summary_.room_changes == 0)
    spdlog::info("walker starts in room '{}' at ({:.2f}, {:.2f}, {:.2f})", to, w.x, w.y, w.z);
  else
    spdlog::info("room '{}' -> '{}' at ({:.2f}, {:.2f}, {:.2f})", from, to, w.x, w.y, w.z);
  // Bounded: a kiosk changes rooms thousands of times a day, so only the latest changes are kept.
  auto& sequence = summary_.room_sequence;
  if (sequence.size() >= Summary::kRoomSequenceKept) sequence.erase(sequence.begin());
  sequence.push_back(to);
  ++summary_.room_changes;
  auto& rooms = summary_.rooms_visited;
  if (std::find(rooms.begin(), rooms.end(), to) == rooms.end()) rooms.push_back(to);
}

void Daemon::poll_devices(double now) {
  // Hardware readings carry CLOCK_MONOTONIC stamps: remember new ones to measure reading -> frame latency.
  auto stamp = [&](const devices::Device& d, int slot, double t) {
    if (!d.monotonic_timestamps() || t <= last_stamp_[slot]) return;
    last_stamp_[slot] = t;
    pending_stamps_.emplace_back(slot, t);
  };
  if (devices_.treadmill) {
    if (auto r = devices_.treadmill->poll(now)) {
      speed_ = r->speed;
      steering_ = r->steering;
      stamp(*devices_.treadmill, 0, r->time);
    } else {
      speed_ = 0.0;  // stale or down: stand still rather than keep walking on an old speed
    }
  }
  if (devices_.head_tracker) {
    if (auto r = devices_.head_tracker->poll(now)) {  // stale: keep looking where the head last was
      yaw_ = r->yaw;
      pitch_ = r->pitch;
      head_live_ = true;
      head_position_.reset();
      if (r->has_position) head_position_ = glm::dvec3(r->x, r->y, r->z);
      stamp(*devices_.head_tracker, 1, r->time);
    } else {
      head_live_ = false;  // screen mode: the eye glides back to the nominal position
      head_position_.reset();
    }
  }
  if (devices_.dimmer_panel)
    if (auto r = devices_.dimmer_panel->poll(now)) {  // the panel keeps its last good levels itself
      for (std::size_t ch = 0; ch < channel_circuit_.size() && ch < r->levels.size(); ++ch)
        levels_[channel_circuit_[ch]] = static_cast<float>(std::clamp(r->levels[ch], 0.0, 1.0));
      stamp(*devices_.dimmer_panel, 2, r->time);
    }
  if (devices_.buttons)
    for (const auto& press : devices_.buttons->poll(now)) {
      spdlog::info("button {} pressed", devices::button_name(press.button));
      if (press.button == devices::Button::ReturnToStart) return_to_start();
      if (press.button == devices::Button::NextBuilding) next_building_ = true;
    }
}

void Daemon::return_to_start() {
  navigator_.return_to_start();
  heading_ = config_.start.heading;
  head_steering_.reset();
  ++summary_.returns_to_start;
}

const devices::Device* Daemon::device(std::size_t role) const {
  switch (role) {
    case 0:
      return devices_.treadmill.get();
    case 1:
      return devices_.head_tracker.get();
    case 2:
      return devices_.dimmer_panel.get();
    default:
      return devices_.buttons.get();
  }
}

std::string Daemon::device_status() const {
  std::string out;
  for (std::size_t i = 0; i < kRoles; ++i)
    if (const auto* d = device(i))
      out += fmt::format("{}{} {}", out.empty() ? "" : ", ", kRoleNames[i], devices::state_name(d->state()));
  return out.empty() ? "no devices" : out;
}

void Daemon::apply(const KioskConfig& config, DeviceSet devices) {
  if (config.bundle != config_.bundle)
    spdlog::warn(
        "{}: bundle changed to {}: a new building needs a restart (systemctl restart walkd); "
        "the rest of the config is applied",
        config.path, config.bundle);
  auto channels = map_channels(config, devices);  // throws before anything changes
  const KioskConfig old = config_;
  config_ = config;
  config_.bundle = old.bundle;  // the walk goes on in the building it is in, from the start it had
  config_.start = old.start;
  config_.buildings = old.buildings;
  devices_ = std::move(devices);
  channel_circuit_ = std::move(channels);
  NavSettings nav = nav_settings(config_.walker);
  navigator_.set_settings(nav);
  for (double& t : last_stamp_) t = -1.0;
  ++summary_.reloads;
  spdlog::info("{}: config reloaded; devices: {}", config_.path, device_status());
}

void Daemon::reload() {
  if (!reload_flag_ || !reload_flag_->exchange(false) || !reload_) return;
  try {
    KioskConfig next = reload_();
    apply(next, open_devices(next.devices));
  } catch (const std::exception& e) {
    spdlog::error("reload failed, keeping the running config: {}", e.what());
  }
}

void Daemon::frame(double now, double dt) {
  poll_devices(now);
  const double speed = speed_, steering = steering_, yaw = yaw_;

  render::View view;
  std::vector<render::View> views;
  if (config_.display.mode == "hmd") {
    // A head-mounted display: the walker goes where the body (start heading + treadmill steering) and the
    // head point together, and the view turns with the head.
    heading_ = config_.start.heading + steering + yaw;
    navigator_.walk(speed, heading_, dt);
    view.eye = navigator_.feet() + glm::dvec3(0, 0, config_.walker.eye_height);
    view.forward = {std::cos(heading_) * std::cos(pitch_), std::sin(heading_) * std::cos(pitch_),
                    std::sin(pitch_)};
    view.fov_y_degrees = config_.display.fov_y_degrees;
    views = stereo_pair(config_, view);
  } else {
    // A fixed screen is a window: head yaw never turns the picture (only, if configured, the walk, as an
    // eased turn rate beyond a dead zone); the eye's position shapes the view through the screen.
    head_steering_.update(head_live_ ? std::optional<double>(yaw) : std::nullopt, dt, config_.steering);
    heading_ = config_.start.heading + steering + head_steering_.turned();
    navigator_.walk(speed, heading_, dt);
    head_coupling_.update(head_position_, dt, config_.display.tracking_ease);
    views = screen_views(config_, navigator_.feet(), heading_, head_coupling_.eye_offset(),
                         head_live_ ? yaw : 0.0);
  }
  track_visits();

  renderer_.set_dimmers(levels_);
  const double t0 = wall_seconds();
  const bool drew = renderer_.draw_views(views);
  renderer_.present(drew);
  summary_.frames_drawn += drew;
  const double shown = devices::monotonic_seconds();
  summary_.render_seconds += wall_seconds() - t0;
  for (const auto& [role, t] : pending_stamps_) latencies_[role].add(shown - t);
  pending_stamps_.clear();
  for (std::size_t i = 0; i < kRoles; ++i)
    if (const devices::Device* d = device(i); d && d->state() != devices::DeviceState::Live)
      ++faulty_frames_[i];
  ++summary_.frames;

  if (config_.output.png_every > 0.0 && now + 1e-9 >= next_png_) {
    const auto name = fmt::format("frame_{:06d}.png", png_requests_);
    saver_.save((std::filesystem::path(config_.output.folder) / name).string(), renderer_.capture(),
                simulated() ? FrameSaver::WhenFull::Wait : FrameSaver::WhenFull::Drop);
    ++png_requests_;
    next_png_ += config_.output.png_every;
  }
}

Summary Daemon::run(const std::atomic<bool>& stop) {
  const bool sim = simulated();
  summary_.mode = sim ? "simulated" : "realtime";
  summary_.renderer = renderer_.name();
  summary_.stopped_by = "end";
  std::error_code ec;
  std::filesystem::create_directories(config_.output.folder, ec);
  if (ec) throw Error(located(config_.output.folder, 0, "cannot create the output folder: " + ec.message()));

  SimulatedClock sim_clock;
  SteadyClock steady_clock;
  const Clock& clock = sim ? static_cast<const Clock&>(sim_clock) : steady_clock;
  const double step = 1.0 / config_.simulation.frame_rate;
  const auto total_frames = static_cast<std::uint64_t>(std::llround(config_.simulation.seconds / step));
  const double wall_start = wall_seconds();
  double last = clock.now();
  track_visits();  // the start room and cell count as visited before the first step

  for (std::uint64_t n = 0;; ++n) {
    if (stop.load()) {
      summary_.stopped_by = "signal";
      break;
    }
    if (renderer_.close_requested()) {
      summary_.stopped_by = "window";
      break;
    }
    if (next_building_) {
      summary_.stopped_by = "next_building";
      break;
    }
    if (sim && n >= total_frames) break;
    reload();
    if (sim) sim_clock.set(static_cast<double>(n) * step);  // frame * step: no accumulated rounding
    const double now = clock.now();
    const double dt = sim ? step : std::min(now - last, kMaxRealtimeStep);
    last = now;
    if (frame_hook_) frame_hook_(now);
    frame(now, dt);

    notifier_.ready();
    const glm::dvec3 w = to_world(navigator_.feet());
    const double wall = wall_seconds() - wall_start;
    notifier_.frame(
        wall, fmt::format("{:.1f} fps, cell {}, room {}, at ({:.2f}, {:.2f}, {:.2f}); {}",
                          summary_.render_seconds > 0 ? summary_.frames_drawn / summary_.render_seconds : 0.0,
                          cell_, room_name(), w.x, w.y, w.z, device_status()));
    summary_.simulated_seconds = sim ? static_cast<double>(n + 1) * step : now;
    if (!sim) {
      // Real time: hold simulation.frame_rate instead of spinning (a window without vsync would burn a core).
      const double left = now + 1.0 / config_.simulation.frame_rate - clock.now();  // reloadable
      if (left > 0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
    }
  }
  notifier_.stopping();
  saver_.flush();  // the frames asked for are on disk before the summary says so
  summary_.frames_saved = saver_.written();
  summary_.frames_not_saved = saver_.dropped() + saver_.failed();

  summary_.wall_seconds = wall_seconds() - wall_start;
  summary_.fps = summary_.render_seconds > 0 ? summary_.frames_drawn / summary_.render_seconds : 0.0;
  summary_.distance = navigator_.distance_walked();
  summary_.final_feet = to_world(navigator_.feet());
  summary_.final_eye = summary_.final_feet + glm::dvec3(0, 0, config_.walker.eye_height);
  summary_.final_heading_deg = heading_ * 180.0 / std::numbers::pi;
  summary_.final_room = room_name();
  summary_.final_cell = cell_;
  summary_.device_states.clear();
  summary_.device_faulty_frames.clear();
  for (std::size_t i = 0; i < kRoles; ++i)
    if (const auto* d = device(i)) {
      summary_.device_states.emplace_back(kRoleNames[i], devices::state_name(d->state()));
      summary_.device_faulty_frames.emplace_back(kRoleNames[i], faulty_frames_[i]);
    }
  LatencyHistogram all;
  for (const auto& l : latencies_) all.merge(l);
  if (all.count()) {
    summary_.latency_p50 = all.quantile(0.5);
    summary_.latency_p99 = all.quantile(0.99);
    summary_.latency_max = all.max();
    summary_.latency_samples = all.count();
  }
  write_summary(config_.output.folder, summary_);
  spdlog::info(
      "stopped ({}): {} frames ({} drawn), {:.1f} s simulated, {:.1f} s wall, {:.1f} fps, {:.1f} m walked, "
      "rooms: {}",
      summary_.stopped_by, summary_.frames, summary_.frames_drawn, summary_.simulated_seconds,
      summary_.wall_seconds, summary_.fps, summary_.distance, fmt::join(summary_.rooms_visited, ", "));
  return summary_;
}

}  // namespace walk::kiosk
