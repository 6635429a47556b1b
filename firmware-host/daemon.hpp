#pragma once
// walkd's main loop as a class a test can drive: poll devices -> navigate -> set dimmers -> render -> save a
// frame every N seconds -> notify systemd, until the simulated end time, a stop request or a closed window.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "firmware-host/clock.hpp"
#include "firmware-host/device_factory.hpp"
#include "firmware-host/frame_renderer.hpp"
#include "firmware-host/frame_saver.hpp"
#include "firmware-host/head_coupling.hpp"
#include "firmware-host/kiosk_config.hpp"
#include "firmware-host/latency_histogram.hpp"
#include "firmware-host/navigation.hpp"
#include "firmware-host/sd_notify.hpp"
#include "firmware-host/summary.hpp"
#include "model/bundle.hpp"

namespace walk::kiosk {

class Daemon {
 public:
  // Places the walker at the configured start and maps dimmer channels to circuits; throws walk::Error
  // naming the config key when the start has no floor or a channel names an unknown circuit.
  Daemon(const KioskConfig& config, const model::Bundle& bundle, FrameRenderer& renderer, DeviceSet devices);

  // Runs the loop and writes summary.json into the output folder, also when stopped early. Returns with
  // stopped_by = "next_building" when that button is pressed (walkd then opens the next building).
  Summary run(const std::atomic<bool>& stop);

  // SIGHUP: when `flag` is set between frames, `load` re-reads the config and the daemon applies it
  // without moving the walker; a config that fails to load or apply is logged and the old one kept.
  void set_reloader(std::atomic<bool>& flag, std::function<KioskConfig()> load) {
    reload_flag_ = &flag;
    reload_ = std::move(load);
  }
  // Called before every frame with the frame's time on the daemon's clock. The soak test drives device
  // polling and fault injection in simulated time through it and samples memory.
  void set_frame_hook(std::function<void(double now)> hook) { frame_hook_ = std::move(hook); }
  // Applies a new config to the running walk: devices reopened, dimmer map, walker, display, output and
  // frame-rate settings. The bundle and start stay (they define the walk). Throws walk::Error if invalid.
  void apply(const KioskConfig& config, DeviceSet devices);

  [[nodiscard]] const KioskConfig& config() const { return config_; }
  [[nodiscard]] const DeviceSet& devices() const { return devices_; }
  // Seconds from a hardware reading's timestamp to the present() of the frame that used it, per role
  // (0 treadmill, 1 head tracker, 2 dimmer panel).
  [[nodiscard]] const LatencyHistogram& latencies(std::size_t role) const { return latencies_[role]; }
  // "treadmill live, head_tracker stale, ..." as the STATUS line shows it.
  [[nodiscard]] std::string device_status() const;

  [[nodiscard]] bool simulated() const { return config_.simulation.seconds > 0.0; }
  [[nodiscard]] const Navigator& navigator() const { return navigator_; }
  [[nodiscard]] Navigator& navigator() { return navigator_; }
  [[nodiscard]] glm::dvec3 to_world(const glm::dvec3& local) const { return local + origin_; }

 private:
  static constexpr std::size_t kRoles = 4;  // treadmill, head_tracker, dimmer_panel, buttons
  static constexpr const char* kRoleNames[kRoles] = {"treadmill", "head_tracker", "dimmer_panel", "buttons"};
  [[nodiscard]] const devices::Device* device(std::size_t role) const;
  void frame(double now, double dt);
  void poll_devices(double now);
  void return_to_start();
  void reload();
  [[nodiscard]] std::vector<std::uint32_t> map_channels(const KioskConfig& config,
                                                        const DeviceSet& devices) const;
  void track_visits();
  [[nodiscard]] std::string room_name() const;

  KioskConfig config_;  // a copy: the caller's config may go out of scope
  const model::Bundle& bundle_;
  FrameRenderer& renderer_;
  DeviceSet devices_;
  glm::dvec3 origin_;
  glm::dvec3 start_{0.0};  // local
  Navigator navigator_;
  SystemdNotifier notifier_;

  std::vector<float> levels_;                   // per circuit
  std::vector<std::uint32_t> channel_circuit_;  // per dimmer channel
  double heading_ = 0.0, pitch_ = 0.0;          // of the gaze, radians
  HeadCoupling head_coupling_;                  // screen mode: the eye's offset, eased
  HeadSteering head_steering_;                  // screen mode: head yaw as a turn rate
  std::optional<glm::dvec3> head_position_;     // live tracker position (tracker frame), if any
  bool head_live_ = false;
  double speed_ = 0.0, steering_ = 0.0, yaw_ = 0.0;  // last good device values (stale treadmill: speed 0)
  bool next_building_ = false;
  std::atomic<bool>* reload_flag_ = nullptr;
  std::function<KioskConfig()> reload_;
  std::function<void(double now)> frame_hook_;
  std::vector<std::pair<int, double>> pending_stamps_;  // (role, hardware reading time) polled this frame
  LatencyHistogram latencies_[3];                       // bounded: a kiosk runs for months
  std::uint64_t faulty_frames_[kRoles] = {};
  double last_stamp_[3] = {-1.0, -1.0, -1.0};  // per treadmill, head tracker, panel: newest reading seen
  double next_png_ = 0.0;
  std::uint64_t png_requests_ = 0;  // names the files: frame_000000.png, ...
  std::uint32_t cell_ = 0;
  std::optional<std::uint32_t> group_;
  FrameSaver saver_;  // PNG encoding off the render thread
  Summary summary_;
};

}  // namespace walk::kiosk
