// The real HidSource: hidapi's hidraw backend. hid_init() is called once, before any reader thread starts.
#include <hidapi/hidapi.h>
#include <spdlog/fmt/fmt.h>

#include <mutex>

#include "devices/hid/hid_device.hpp"

namespace walk::devices {
namespace {

std::string narrow(const wchar_t* w) {
  if (!w) return "unknown error";
  std::string s;
  for (; *w; ++w) s.push_back(*w < 128 ? static_cast<char>(*w) : '?');
  return s;
}

class HidapiSource final : public HidSource {
 public:
  explicit HidapiSource(const HidDeviceConfig& c) : config_(c) {
    static std::once_flag once;
    std::call_once(once, [] { hid_init(); });
  }
  ~HidapiSource() override { close(); }

  std::string open() override {
    close();
    if (!config_.path.empty()) {
      dev_ = hid_open_path(config_.path.c_str());
    } else {
      std::wstring serial(config_.serial.begin(), config_.serial.end());
      dev_ = hid_open(config_.vendor_id, config_.product_id, serial.empty() ? nullptr : serial.c_str());
    }
    if (!dev_)
      return describe() + ": cannot open: " + narrow(hid_error(nullptr)) +
             " (is it plugged in, and does the udev rule give the walkd group access?)";
    return {};
  }
  int read(std::span<std::uint8_t> buffer, int timeout_ms) override {
    if (!dev_) return -1;
    return hid_read_timeout(dev_, buffer.data(), buffer.size(), timeout_ms);
  }
  void close() override {
    if (dev_) hid_close(dev_);
    dev_ = nullptr;
  }
  [[nodiscard]] std::string error() const override { return narrow(hid_error(dev_)); }
  [[nodiscard]] std::string describe() const override {
    return config_.path.empty() ? fmt::format("hid {:04x}:{:04x}", config_.vendor_id, config_.product_id)
                                : "hid " + config_.path;
  }

 private:
  HidDeviceConfig config_;
  hid_device* dev_ = nullptr;
};

}  // namespace

std::unique_ptr<HidSource> make_hidapi_source(const HidDeviceConfig& config) {
  return std::make_unique<HidapiSource>(config);
}

}  // namespace walk::devices
