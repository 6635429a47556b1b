#pragma once
// A dimmer panel over Modbus (libmodbus), RTU on a serial line or TCP. A poller thread reads the channel
// registers at the configured rate; each read gets a response timeout and a number of immediate retries,
// after which the connection is dropped and reopened with backoff. The newest good levels stay in use
// while the panel is stale or down (the lights do not jump when a cable is pulled).
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "devices/devices.hpp"
#include "devices/fault.hpp"
#include "devices/reader_thread.hpp"

typedef struct _modbus modbus_t;

namespace walk::devices {

struct ModbusPanelConfig {
  enum class Transport { Tcp, Rtu } transport = Transport::Tcp;
  std::string host = "127.0.0.1";  // TCP
  int port = 502;
  std::string device;  // RTU: /dev/ttyUSB0
  int baud = 19200;
  char parity = 'E';  // Modbus RTU default 8E1
  int data_bits = 8, stop_bits = 1;
  int slave = 1;
  bool input_registers = false;  // function 04 instead of 03 (holding registers)
  std::vector<int> registers;    // register address of each channel
  double full_scale = 1000.0;    // raw value of level 1.0; above it is garbage
  double poll_hz = 20.0;
  double timeout = 0.1;  // response timeout, seconds
  int retries = 2;       // immediate retries of a failed read before reconnecting
  FaultPolicy faults;
};

class ModbusDimmerPanel final : public DimmerPanel {
 public:
  using TimeFn = std::function<double()>;
  explicit ModbusDimmerPanel(ModbusPanelConfig config, TimeFn clock = monotonic_seconds);
  ~ModbusDimmerPanel() override;

  void start();  // poller thread: step() at poll_hz
  // One poll: connect if due, read the registers (with retries). True when levels were read.
  bool step();

  [[nodiscard]] std::size_t channel_count() const override { return config_.registers.size(); }
  std::optional<DimmerReading> poll(double now) override;  // newest good levels, also when stale
  [[nodiscard]] DeviceState state() const override { return faults_.state(clock_()); }
  [[nodiscard]] std::string name() const override { return faults_.device(); }
  [[nodiscard]] const FaultTracker& faults() const { return faults_; }
  [[nodiscard]] std::vector<double> round_trips() const;  // seconds of each good read (last 4096)
  [[nodiscard]] std::uint64_t reads() const;

 private:
  bool connect(double now);
  void disconnect();

  ModbusPanelConfig config_;
  TimeFn clock_;
  FaultTracker faults_;
  modbus_t* ctx_ = nullptr;   // poller only
  int first_ = 0, span_ = 0;  // one request covers all channel registers when they lie close together
  mutable std::mutex mutex_;
  std::optional<DimmerReading> latest_;
  std::vector<double> round_trips_;
  std::uint64_t reads_ = 0;
  ReaderThread thread_;
};

}  // namespace walk::devices
