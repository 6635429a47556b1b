#pragma once
// HID treadmills and head trackers through hidapi (hidraw). The report layout comes from config; a reader
// thread reads reports as they arrive (timestamped on arrival), decodes them and keeps the newest good one.
// The HidSource seam lets tests feed raw report bytes where there is no /dev/uhid.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "devices/devices.hpp"
#include "devices/fault.hpp"
#include "devices/hid/report_layout.hpp"
#include "devices/reader_thread.hpp"

namespace walk::devices {

struct HidDeviceConfig {
  std::string path;             // /dev/hidraw0 (or a hidapi path) ...
  std::uint16_t vendor_id = 0;  // ... or vendor:product (+ serial) to find it wherever it is plugged in
  std::uint16_t product_id = 0;
  std::string serial;
  HidReportLayout layout;
  FaultPolicy faults;
  int read_timeout_ms = 50;  // bounds one reader step (how fast the thread notices a stop)
};

class HidSource {
 public:
  virtual ~HidSource() = default;
  [[nodiscard]] virtual std::string open() = 0;  // empty on success, else why not
  // Bytes read (> 0), 0 on timeout, < 0 when the device failed or went away.
  virtual int read(std::span<std::uint8_t> buffer, int timeout_ms) = 0;
  virtual void close() = 0;
  [[nodiscard]] virtual std::string error() const = 0;  // after a failed read
  [[nodiscard]] virtual std::string describe() const = 0;
};

[[nodiscard]] std::unique_ptr<HidSource> make_hidapi_source(const HidDeviceConfig& config);

class HidReader {
 public:
  using TimeFn = std::function<double()>;
  HidReader(std::string name, std::unique_ptr<HidSource> source, HidReportLayout layout, FaultPolicy policy,
            TimeFn clock = monotonic_seconds);
  ~HidReader() { thread_.stop(); }

  void start(int timeout_ms);  // reader thread calling step(timeout_ms)
  void step(int timeout_ms);   // reopen when due, read at most one report, decode it

  struct Sample {
    double time = 0.0;
    std::vector<double> values;  // per layout field
  };
  [[nodiscard]] std::optional<Sample> latest() const;  // the newest good report while Live
  [[nodiscard]] DeviceState state() const { return faults_.state(clock_()); }
  [[nodiscard]] const FaultTracker& faults() const { return faults_; }
  [[nodiscard]] const HidReportLayout& layout() const { return layout_; }
  [[nodiscard]] std::uint64_t reports() const;  // good reports decoded

 private:
  std::unique_ptr<HidSource> source_;
  HidReportLayout layout_;
  FaultTracker faults_;
  TimeFn clock_;
  bool open_ = false;  // touched by the reader only
  std::vector<std::uint8_t> buffer_;
  mutable std::mutex mutex_;
  std::optional<Sample> sample_;
  std::uint64_t reports_ = 0;
  ReaderThread thread_;
};

// Fields: `speed` (m/s, required) and `steering` (radians, optional).
class HidTreadmill final : public Treadmill {
 public:
  explicit HidTreadmill(std::unique_ptr<HidReader> reader);
  std::optional<TreadmillReading> poll(double now) override;
  [[nodiscard]] DeviceState state() const override { return reader_->state(); }
  [[nodiscard]] std::string name() const override { return reader_->faults().device(); }
  [[nodiscard]] HidReader& reader() { return *reader_; }

 private:
  std::unique_ptr<HidReader> reader_;
  std::size_t speed_, steering_;
};

// Fields: `yaw` (radians, required), `pitch` (optional), `x`, `y`, `z` (metres, optional, all three).
class HidHeadTracker final : public HeadTracker {
 public:
  explicit HidHeadTracker(std::unique_ptr<HidReader> reader);
  std::optional<HeadReading> poll(double now) override;
  [[nodiscard]] DeviceState state() const override { return reader_->state(); }
  [[nodiscard]] std::string name() const override { return reader_->faults().device(); }
  [[nodiscard]] HidReader& reader() { return *reader_; }

 private:
  std::unique_ptr<HidReader> reader_;
  std::size_t yaw_, pitch_, x_, y_, z_;
};

}  // namespace walk::devices
