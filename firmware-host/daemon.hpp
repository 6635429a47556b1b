#pragma once
// walkd's main loop as a class a test can drive: poll devices -> navigate -> set dimmers -> render -> save a
// frame every N seconds -> notify systemd, until the simulated end time, a stop request or a closed window.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "firmware-host/clock.hpp"
#include "firmware-host/device_factory.hpp"
#include "firmware-host/frame_renderer.hpp"
#include "firmware-host/kiosk_config.hpp"
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

  // Runs the loop and writes summary.json into the output folder, also when stopped early.
  Summary run(const std::atomic<bool>& stop);

  [[nodiscard]] bool simulated() const { return config_.simulation.seconds > 0.0; }
  [[nodiscard]] const Navigator& navigator() const { return navigator_; }
  [[nodiscard]] Navigator& navigator() { return navigator_; }
  [[nodiscard]] glm::dvec3 to_world(const glm::dvec3& local) const { return local + origin_; }

 private:
  void frame(double now, double dt);
  void track_visits();
  [[nodiscard]] std::string room_name() const;

  const KioskConfig config_;  // a copy: the caller's config may go out of scope
  const model::Bundle& bundle_;
  FrameRenderer& renderer_;
  DeviceSet devices_;
  glm::dvec3 origin_;
  Navigator navigator_;
  SystemdNotifier notifier_;

  std::vector<float> levels_;                   // per circuit
  std::vector<std::uint32_t> channel_circuit_;  // per dimmer channel
  double heading_ = 0.0, pitch_ = 0.0;          // of the gaze, radians
  double next_png_ = 0.0;
  std::uint32_t cell_ = 0;
  std::optional<std::uint32_t> group_;
  Summary summary_;
};

}  // namespace walk::kiosk
