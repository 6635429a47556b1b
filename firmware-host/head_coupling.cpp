#include "firmware-host/head_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace walk::kiosk {
namespace {

// The nominal screen stands this far in front of the nominal eye (metres). Any distance gives the same
// picture at rest; 1 m keeps head movements of a few centimetres in proportion for a desk-size default.
constexpr double kNominalScreenDistance = 1.0;
// A head on a treadmill stays within this of its rest position (metres, per axis); a tracker reporting more
// is clamped rather than trusted to fling the picture.
constexpr double kMaxHeadOffset = 1.0;
// The eye is kept at least this far in front of the screen plane (metres): at zero the frustum is infinite.
constexpr double kMinEyeToScreen = 0.05;

// Tracker frame -> local building coordinates for a walker at `feet` facing `heading`.
glm::dvec3 to_building(const glm::dvec3& p, const glm::dvec3& feet, double heading) {
  const glm::dvec3 forward(std::cos(heading), std::sin(heading), 0.0);
  const glm::dvec3 right(std::sin(heading), -std::cos(heading), 0.0);
  return feet + p.x * right + p.y * forward + glm::dvec3(0.0, 0.0, p.z);
}

}  // namespace

glm::dvec3 nominal_eye(const KioskConfig& config) {
  return config.display.nominal_eye.value_or(glm::dvec3(0.0, 0.0, config.walker.eye_height));
}

std::vector<render::ScreenRect> screens_in_tracker_frame(const KioskConfig& config) {
  std::vector<render::ScreenRect> out;
  for (const auto& c : config.display.screens) out.push_back({c.lower_left, c.lower_right, c.upper_left});
  if (out.empty()) out.push_back(screen_in_tracker_frame(config));
  return out;
}

bool stereo(const KioskConfig& config) {
  return config.display.stereo != "off";
}

render::ScreenRect screen_in_tracker_frame(const KioskConfig& config) {
  if (const auto& c = config.display.screen) return {c->lower_left, c->lower_right, c->upper_left};
  const glm::dvec3 eye = nominal_eye(config);
  const double half_h = kNominalScreenDistance * std::tan(config.display.fov_y_degrees * M_PI / 360.0);
  const double half_w = half_h * double(config.display.width) / double(config.display.height);
  const double y = eye.y + kNominalScreenDistance;
  return {{eye.x - half_w, y, eye.z - half_h},
          {eye.x + half_w, y, eye.z - half_h},
          {eye.x - half_w, y, eye.z + half_h}};
}

void HeadCoupling::update(const std::optional<glm::dvec3>& head_offset, double dt, double ease_seconds) {
  // Linear in time: a lost tracker takes exactly ease_seconds to hand the eye back to the nominal position.
  const double step = ease_seconds > 0.0 ? dt / ease_seconds : 1.0;
  if (head_offset) {
    last_tracked_ = *head_offset;
    weight_ = std::min(1.0, weight_ + step);
  } else {
    weight_ = std::max(0.0, weight_ - step);
  }
}

void HeadSteering::update(std::optional<double> yaw, double dt, const SteeringConfig& config) {
  double target = 0.0;
  if (config.head_turn && yaw) {
    const double excess = std::abs(*yaw) - config.dead_zone;
    if (excess > 0.0) target = std::copysign(std::min(config.turn_gain * excess, config.max_turn_rate), *yaw);
  }
  // First-order easing of the rate: the turn starts and stops smoothly, which big screens need to keep
  // people from feeling sick.
  const double k = config.ease_seconds > 0.0 ? 1.0 - std::exp(-dt / config.ease_seconds) : 1.0;
  rate_ += (target - rate_) * k;
  turned_ += rate_ * dt;
}

namespace {

// The view through screen `s` (tracker frame) from nominal eye + offset, for a walker at feet facing heading.
render::View view_through(const KioskConfig& config, const render::ScreenRect& s, const glm::dvec3& feet,
                          double heading, const glm::dvec3& eye_offset) {
  glm::dvec3 eye = nominal_eye(config) + glm::clamp(eye_offset, -kMaxHeadOffset, kMaxHeadOffset);
  const glm::dvec3 towards_viewer =
      glm::normalize(glm::cross(s.lower_right - s.lower_left, s.upper_left - s.lower_left));
  if (const double d = glm::dot(eye - s.lower_left, towards_viewer); d < kMinEyeToScreen)
    eye += (kMinEyeToScreen - d) * towards_viewer;
  render::View view;
  view.eye = to_building(eye, feet, heading);
  view.forward = {std::cos(heading), std::sin(heading), 0.0};
  view.fov_y_degrees = config.display.fov_y_degrees;
  view.screen =
      render::ScreenRect{to_building(s.lower_left, feet, heading), to_building(s.lower_right, feet, heading),
                         to_building(s.upper_left, feet, heading)};
  return view;
}

}  // namespace

render::View screen_view(const KioskConfig& config, const glm::dvec3& feet, double heading,
                         const glm::dvec3& eye_offset, std::size_t screen) {
  return view_through(config, screens_in_tracker_frame(config).at(screen), feet, heading, eye_offset);
}

std::vector<render::View> screen_views(const KioskConfig& config, const glm::dvec3& feet, double heading,
                                       const glm::dvec3& eye_offset, double head_yaw) {
  std::vector<render::View> views;
  // The eyes sit either side of the head along its right axis: the tracker's x turned by the head's yaw.
  const glm::dvec3 half_eyes =
      0.5 * config.display.eye_separation * glm::dvec3(std::cos(head_yaw), std::sin(head_yaw), 0.0);
  for (const render::ScreenRect& s : screens_in_tracker_frame(config)) {
    if (!stereo(config)) {
      views.push_back(view_through(config, s, feet, heading, eye_offset));
      continue;
    }
    views.push_back(view_through(config, s, feet, heading, eye_offset - half_eyes));
    views.push_back(view_through(config, s, feet, heading, eye_offset + half_eyes));
  }
  return views;
}

std::vector<render::View> stereo_pair(const KioskConfig& config, const render::View& centre) {
  if (!stereo(config)) return {centre};
  glm::dvec3 right = glm::cross(centre.forward, centre.up);
  right = glm::length(right) > 1e-9 ? glm::normalize(right) : glm::dvec3(1.0, 0.0, 0.0);
  render::View left = centre, right_eye = centre;
  left.eye -= 0.5 * config.display.eye_separation * right;
  right_eye.eye += 0.5 * config.display.eye_separation * right;
  return {left, right_eye};
}

}  // namespace walk::kiosk
