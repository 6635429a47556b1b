#include "devices/hid/hid_device.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>

#include "model/error.hpp"

namespace walk::devices {

HidReader::HidReader(std::string name, std::unique_ptr<HidSource> source, HidReportLayout layout,
                     FaultPolicy policy, TimeFn clock)
    : source_(std::move(source)),
      layout_(std::move(layout)),
      faults_(std::move(name), policy),
      clock_(std::move(clock)),
      buffer_(std::max<std::size_t>(layout_.length, 64) + 1) {
  if (const auto problem = layout_.check(); !problem.empty())
    throw Error(faults_.device() + ": report layout: " + problem +
                " (fix the device's [report] in the kiosk config)");
}

void HidReader::start(int timeout_ms) {
  thread_.start([this, timeout_ms] { step(timeout_ms); });
}

void HidReader::step(int timeout_ms) {
  double now = clock_();
  const bool was_open = open_;
  if (!ensure_open(*source_, open_, faults_, now, thread_.running(), timeout_ms)) return;
  if (!was_open) faults_.opened();  // stale until the first good report
  const int n = source_->read(buffer_, timeout_ms);
  now = clock_();
  if (n < 0) {
    faults_.down(now, source_->describe() + ": " + source_->error());
    source_->close();
    open_ = false;
    return;
  }
  if (n == 0) {
    if (faults_.state(now) == DeviceState::Stale)
      faults_.timeout(now, fmt::format("no report for {:g} s", faults_.policy().stale_after));
    return;
  }
  const auto d = decode_report(layout_, std::span(buffer_.data(), static_cast<std::size_t>(n)));
  if (d.status == HidDecode::OtherReport) return;
  if (d.status != HidDecode::Ok) {
    faults_.garbage(now, d.why);
    return;
  }
  faults_.good(now);
  std::lock_guard lock(mutex_);
  sample_ = Sample{now, d.values};
  ++reports_;
}

std::optional<HidReader::Sample> HidReader::latest() const {
  if (state() != DeviceState::Live) return std::nullopt;
  std::lock_guard lock(mutex_);
  return sample_;
}

std::uint64_t HidReader::reports() const {
  std::lock_guard lock(mutex_);
  return reports_;
}

namespace {

std::size_t required(const HidReader& r, const char* field) {
  const auto i = r.layout().field(field);
  if (i == HidReportLayout::npos)
    throw Error(
        fmt::format("{}: the report layout has no '{}' field (add it under the device's report fields)",
                    r.faults().device(), field));
  return i;
}

}  // namespace

HidTreadmill::HidTreadmill(std::unique_ptr<HidReader> reader)
    : reader_(std::move(reader)),
      speed_(required(*reader_, "speed")),
      steering_(reader_->layout().field("steering")) {}

std::optional<TreadmillReading> HidTreadmill::poll(double) {
  const auto s = reader_->latest();
  if (!s) return std::nullopt;
  TreadmillReading r;
  r.time = s->time;
  r.speed = std::max(0.0, s->values[speed_]);
  if (steering_ != HidReportLayout::npos) r.steering = s->values[steering_];
  return r;
}

HidHeadTracker::HidHeadTracker(std::unique_ptr<HidReader> reader)
    : reader_(std::move(reader)),
      yaw_(required(*reader_, "yaw")),
      pitch_(reader_->layout().field("pitch")),
      x_(reader_->layout().field("x")),
      y_(reader_->layout().field("y")),
      z_(reader_->layout().field("z")) {}

std::optional<HeadReading> HidHeadTracker::poll(double) {
  const auto s = reader_->latest();
  if (!s) return std::nullopt;
  HeadReading r;
  r.time = s->time;
  r.yaw = s->values[yaw_];
  if (pitch_ != HidReportLayout::npos) r.pitch = s->values[pitch_];
  if (x_ != HidReportLayout::npos && y_ != HidReportLayout::npos && z_ != HidReportLayout::npos) {
    r.has_position = true;
    r.x = s->values[x_];
    r.y = s->values[y_];
    r.z = s->values[z_];
  }
  return r;
}

}  // namespace walk::devices
