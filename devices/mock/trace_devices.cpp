#include "devices/mock/trace_devices.hpp"

#include <spdlog/fmt/fmt.h>

#include <numbers>

#include "model/error.hpp"

namespace walk::devices {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

void check_range(const CsvTrace& trace, std::size_t column, double lo, double hi, const std::string& what) {
  for (std::size_t row = 0; row < trace.size(); ++row) {
    const double v = trace.value(row, column);
    if (v < lo || v > hi)
      throw Error(located(trace.path(), trace.line(row),
                          fmt::format("{} {:g} is outside {:g}..{:g}", what, v, lo, hi)));
  }
}

}  // namespace

TraceTreadmill::TraceTreadmill(const std::string& path)
    : trace_(CsvTrace::load(path, {"speed"}, {"steering_deg"})),
      speed_(trace_.column("speed")),
      steering_(trace_.column("steering_deg")) {
  check_range(trace_, speed_, 0.0, 10.0, "speed");
}

std::optional<TreadmillReading> TraceTreadmill::poll(double now) {
  const auto row = trace_.row_at(now);
  if (row == CsvTrace::npos) return std::nullopt;
  TreadmillReading r;
  r.time = trace_.time(row);
  r.speed = trace_.value(row, speed_);
  r.steering = steering_ == CsvTrace::npos ? 0.0 : trace_.value(row, steering_) * kDegrees;
  return r;
}

TraceHeadTracker::TraceHeadTracker(const std::string& path)
    : trace_(CsvTrace::load(path, {"yaw_deg"}, {"pitch_deg", "x_m", "y_m", "z_m"})),
      yaw_(trace_.column("yaw_deg")),
      pitch_(trace_.column("pitch_deg")),
      position_{trace_.column("x_m"), trace_.column("y_m"), trace_.column("z_m")} {
  if (pitch_ != CsvTrace::npos) check_range(trace_, pitch_, -90.0, 90.0, "pitch_deg");
  const int given = int(position_[0] != CsvTrace::npos) + int(position_[1] != CsvTrace::npos) +
                    int(position_[2] != CsvTrace::npos);
  if (given != 0 && given != 3)
    throw Error(located(path, 1, "head position needs all of x_m, y_m and z_m", "add the missing columns"));
  // A head on a treadmill moves centimetres to decimetres from its rest position; metres are a unit mistake.
  for (std::size_t c = 0; c < 3 && given == 3; ++c)
    check_range(trace_, position_[c], -2.0, 2.0, trace_.columns()[position_[c]]);
}

std::optional<HeadReading> TraceHeadTracker::poll(double now) {
  const auto row = trace_.row_at(now);
  if (row == CsvTrace::npos) return std::nullopt;
  HeadReading r;
  r.time = trace_.time(row);
  r.yaw = trace_.value(row, yaw_) * kDegrees;
  r.pitch = pitch_ == CsvTrace::npos ? 0.0 : trace_.value(row, pitch_) * kDegrees;
  if (position_[0] != CsvTrace::npos) {
    r.has_position = true;
    r.x = trace_.value(row, position_[0]);
    r.y = trace_.value(row, position_[1]);
    r.z = trace_.value(row, position_[2]);
  }
  return r;
}

TraceDimmerPanel::TraceDimmerPanel(const std::string& path) : trace_(CsvTrace::load(path, {}, {}, true)) {
  const auto& columns = trace_.columns();
  if (columns.empty()) throw Error(located(path, 1, "no channel columns", "expected time,ch0,ch1,..."));
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] != "ch" + std::to_string(i))
      throw Error(located(path, 1, "column '" + columns[i] + "' should be 'ch" + std::to_string(i) + "'",
                          "channels are named ch0, ch1, ... in order"));
    check_range(trace_, i, 0.0, 1.0, columns[i]);
  }
}

std::optional<DimmerReading> TraceDimmerPanel::poll(double now) {
  const auto row = trace_.row_at(now);
  if (row == CsvTrace::npos) return std::nullopt;
  DimmerReading r;
  r.time = trace_.time(row);
  r.levels.resize(channel_count());
  for (std::size_t i = 0; i < r.levels.size(); ++i) r.levels[i] = trace_.value(row, i);
  return r;
}

TraceButtons::TraceButtons(const std::string& path) : trace_(CsvTrace::load(path, {"button"})) {
  check_range(trace_, 0, 0.0, static_cast<double>(kButtonCount - 1), "button");
}

std::vector<ButtonPress> TraceButtons::poll(double now) {
  std::vector<ButtonPress> out;
  for (; next_ < trace_.size() && trace_.time(next_) <= now; ++next_)
    out.push_back({trace_.time(next_), static_cast<Button>(static_cast<int>(trace_.value(next_, 0)))});
  return out;
}

}  // namespace walk::devices
