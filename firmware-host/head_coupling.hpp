#pragma once
// The big screen as a window (display.mode = "screen"): the picture is the view through the physical screen
// from where the tracked eye is (off-axis perspective, Kooima 2008), and the walking direction comes from the
// treadmill's steering or from head yaw as an eased turn rate, never from the head's yaw directly.
//
// Tracker frame: metres, x to the walker's right, y forward towards the screen, z up, origin on the treadmill
// belt where the walker stands. In the building it moves with the walker: its origin at the walker's feet,
// its y axis along the walking heading.
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "firmware-host/kiosk_config.hpp"
#include "render/renderer.hpp"

namespace walk::kiosk {

// The screen's corners in the tracker frame: the configured ones, or a nominal screen 1 m in front of the
// nominal eye spanning fov_y_deg at the output's aspect (what hmd mode shows while the head is at rest).
[[nodiscard]] render::ScreenRect screen_in_tracker_frame(const KioskConfig& config);
[[nodiscard]] glm::dvec3 nominal_eye(const KioskConfig& config);

// Eye position: the tracker's while it reports one, gliding to and from the nominal eye over ease_seconds
// when tracking is lost or regained, so the picture never jumps.
class HeadCoupling {
 public:
  // head_offset: the live reading's offset from the rest position, or nothing (no position, stale, down).
  void update(const std::optional<glm::dvec3>& head_offset, double dt, double ease_seconds);
  // Offset of the eye from the nominal eye, tracker frame.
  [[nodiscard]] glm::dvec3 eye_offset() const { return weight_ * last_tracked_; }
  [[nodiscard]] double tracking_weight() const { return weight_; }

 private:
  glm::dvec3 last_tracked_{0.0};
  double weight_ = 0.0;  // 1: the tracked position, 0: the nominal eye
};

// Head yaw beyond the dead zone turns the walker at a rate that grows with the excess, eased in and out.
class HeadSteering {
 public:
  // yaw: radians, left positive; nothing while the head tracker is not live (the turn eases to a stop).
  void update(std::optional<double> yaw, double dt, const SteeringConfig& config);
  [[nodiscard]] double turned() const { return turned_; }  // radians turned so far, left positive
  [[nodiscard]] double rate() const { return rate_; }      // radians per second now
  void reset() { turned_ = rate_ = 0.0; }

 private:
  double turned_ = 0.0, rate_ = 0.0;
};

// Every screen in the tracker frame: [[display.screens]] in order, or the one screen above.
[[nodiscard]] std::vector<render::ScreenRect> screens_in_tracker_frame(const KioskConfig& config);

// Views per frame: for each screen, one eye (mono) or the left then the right eye (stereo), the eyes
// eye_separation apart along the head's right axis (the tracker's x turned by the head's yaw).
[[nodiscard]] std::vector<render::View> screen_views(const KioskConfig& config, const glm::dvec3& feet,
                                                     double heading, const glm::dvec3& eye_offset,
                                                     double head_yaw);
// hmd mode: the one view, or its left and right eyes.
[[nodiscard]] std::vector<render::View> stereo_pair(const KioskConfig& config, const render::View& centre);
[[nodiscard]] bool stereo(const KioskConfig& config);

// The view for a walker with feet at `feet` (local metres) facing `heading`, eye at nominal + offset.
[[nodiscard]] render::View screen_view(const KioskConfig& config, const glm::dvec3& feet, double heading,
                                       const glm::dvec3& eye_offset, std::size_t screen = 0);

}  // namespace walk::kiosk
