#pragma once
// A dimmer-panel simulator that speaks real Modbus (libmodbus server): on TCP (bind 127.0.0.1, port 0 picks
// a free one) or RTU on a serial device such as one end of a socat pty pair. Holding and input registers
// mirror each other, so either read function works. Tests change registers while walkd polls.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

typedef struct _modbus modbus_t;
typedef struct _modbus_mapping_t modbus_mapping_t;

namespace walk::devices {

class PanelSimulator {
 public:
  // Throws walk::Error when it cannot listen / open the device.
  static std::unique_ptr<PanelSimulator> tcp(const std::string& host, int port, int registers, int slave = 1);
  static std::unique_ptr<PanelSimulator> rtu(const std::string& device, int baud, char parity, int registers,
                                             int slave = 1);
  ~PanelSimulator();
  PanelSimulator(const PanelSimulator&) = delete;
  PanelSimulator& operator=(const PanelSimulator&) = delete;

  void set_register(int address, std::uint16_t value);
  [[nodiscard]] std::uint16_t get_register(int address) const;
  void set_silent(bool silent) { silent_ = silent; }  // receives but never answers: a hung panel
  void stop();                                        // closes every connection at once, like a crash
  [[nodiscard]] int port() const { return port_; }
  [[nodiscard]] std::uint64_t requests() const { return requests_; }

  // Blocks serving until stop() or `stop_flag`: for the walk-panel-sim program.
  void serve(const std::atomic<bool>& stop_flag);

 private:
  PanelSimulator() = default;
  void serve_tcp(const std::atomic<bool>& stop_flag);
  void serve_rtu(const std::atomic<bool>& stop_flag);
  void handle(modbus_t* ctx);

  bool rtu_ = false;
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* map_ = nullptr;
  int listen_fd_ = -1;
  int port_ = 0;
  mutable std::mutex mutex_;
  std::atomic<bool> stopping_{false}, silent_{false};
  std::atomic<std::uint64_t> requests_{0};
  std::thread thread_;
};

}  // namespace walk::devices
