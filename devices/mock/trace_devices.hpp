#pragma once
// Mock devices that replay recorded CSV traces: deterministic input for simulated runs and tests.
// Columns: treadmill `time,speed[,steering_deg]`; head tracker `time,yaw_deg[,pitch_deg][,x_m,y_m,z_m]`
// (position: the head's offset from rest in the tracker frame, metres);
// dimmer panel `time,ch0,ch1,...` (levels 0..1); buttons `time,button` (0 = return_to_start, 1 =
// next_building). Angles are degrees in the file, radians in readings.
#include <memory>
#include <string>

#include "devices/devices.hpp"
#include "devices/mock/csv_trace.hpp"

namespace walk::devices {

class TraceTreadmill final : public Treadmill {
 public:
  explicit TraceTreadmill(const std::string& path);
  std::optional<TreadmillReading> poll(double now) override;
  [[nodiscard]] bool monotonic_timestamps() const override { return false; }
  [[nodiscard]] std::string name() const override { return "treadmill (mock " + trace_.path() + ")"; }

 private:
  CsvTrace trace_;
  std::size_t speed_, steering_;
};

class TraceHeadTracker final : public HeadTracker {
 public:
  explicit TraceHeadTracker(const std::string& path);
  std::optional<HeadReading> poll(double now) override;
  [[nodiscard]] bool monotonic_timestamps() const override { return false; }
  [[nodiscard]] std::string name() const override { return "head tracker (mock " + trace_.path() + ")"; }

 private:
  CsvTrace trace_;
  std::size_t yaw_, pitch_;
  std::size_t position_[3];  // x_m, y_m, z_m: the head's offset from rest, tracker frame; npos if absent
};

class TraceDimmerPanel final : public DimmerPanel {
 public:
  explicit TraceDimmerPanel(const std::string& path);
  [[nodiscard]] std::size_t channel_count() const override { return trace_.columns().size(); }
  std::optional<DimmerReading> poll(double now) override;
  [[nodiscard]] bool monotonic_timestamps() const override { return false; }
  [[nodiscard]] std::string name() const override { return "dimmer panel (mock " + trace_.path() + ")"; }

 private:
  CsvTrace trace_;
};

// Presses replayed from `time,button` rows (button: 0 = return_to_start, 1 = next_building); each row is
// reported once, by the first poll at or after its time.
class TraceButtons final : public ButtonPanel {
 public:
  explicit TraceButtons(const std::string& path);
  std::vector<ButtonPress> poll(double now) override;
  [[nodiscard]] bool monotonic_timestamps() const override { return false; }
  [[nodiscard]] std::string name() const override { return "buttons (mock " + trace_.path() + ")"; }

 private:
  CsvTrace trace_;
  std::size_t next_ = 0;
};

}  // namespace walk::devices
