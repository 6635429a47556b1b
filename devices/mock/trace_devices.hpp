#pragma once
// Mock devices that replay recorded CSV traces: deterministic input for simulated runs and tests.
// Columns: treadmill `time,speed[,steering_deg]`; head tracker `time,yaw_deg[,pitch_deg]`;
// dimmer panel `time,ch0,ch1,...` (levels 0..1). Angles are degrees in the file, radians in readings.
#include <memory>
#include <string>

#include "devices/devices.hpp"
#include "devices/mock/csv_trace.hpp"

namespace walk::devices {

class TraceTreadmill final : public Treadmill {
 public:
  explicit TraceTreadmill(const std::string& path);
  std::optional<TreadmillReading> poll(double now) override;

 private:
  CsvTrace trace_;
  std::size_t speed_, steering_;
};

class TraceHeadTracker final : public HeadTracker {
 public:
  explicit TraceHeadTracker(const std::string& path);
  std::optional<HeadReading> poll(double now) override;

 private:
  CsvTrace trace_;
  std::size_t yaw_, pitch_;
};

class TraceDimmerPanel final : public DimmerPanel {
 public:
  explicit TraceDimmerPanel(const std::string& path);
  [[nodiscard]] std::size_t channel_count() const override { return trace_.columns().size(); }
  std::optional<DimmerReading> poll(double now) override;

 private:
  CsvTrace trace_;
};

}  // namespace walk::devices
