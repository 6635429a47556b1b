// The real GpioSource: libgpiod v1 (Debian 12 ships 1.6). One event fd per line, polled together.
#include <gpiod.h>
#include <poll.h>

#include <cerrno>
#include <cstring>

#include "devices/gpio/gpio_device.hpp"

namespace walk::devices {
namespace {

class GpiodSource final : public GpioSource {
 public:
  GpiodSource(std::string chip, std::vector<unsigned> lines, bool active_low, std::string consumer)
      : chip_name_(std::move(chip)),
        offsets_(std::move(lines)),
        active_low_(active_low),
        consumer_(std::move(consumer)) {}
  ~GpiodSource() override { close(); }

  std::string open() override {
    close();
    chip_ = gpiod_chip_open_lookup(chip_name_.c_str());
    if (!chip_)
      return describe() + ": cannot open the chip: " + std::strerror(errno) +
             " (gpiodetect lists chips; does the udev rule give the walkd group access?)";
    for (unsigned offset : offsets_) {
      gpiod_line* line = gpiod_chip_get_line(chip_, offset);
      const int flags = active_low_ ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
      if (!line || gpiod_line_request_both_edges_events_flags(line, consumer_.c_str(), flags) < 0) {
        const std::string why = describe() + ": cannot request line " + std::to_string(offset) +
                                " for edge events: " + std::strerror(errno) +
                                " (is another program using it?)";
        close();
        return why;
      }
      lines_.push_back(line);
    }
    return {};
  }

  int wait(int timeout_ms, std::vector<LineEvent>& out) override {
    std::vector<pollfd> fds;
    for (gpiod_line* l : lines_) fds.push_back({gpiod_line_event_get_fd(l), POLLIN | POLLPRI, 0});
    const int r = ::poll(fds.data(), fds.size(), timeout_ms);
    if (r < 0) {
      if (errno == EINTR) return 0;
      errno_ = errno;
      return -1;
    }
    int n = 0;
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents & (POLLERR | POLLHUP | POLLNVAL)) {
        errno_ = ENODEV;
        return -1;
      }
      if (!(fds[i].revents & (POLLIN | POLLPRI))) continue;
      gpiod_line_event ev{};
      if (gpiod_line_event_read(lines_[i], &ev) < 0) {
        errno_ = errno;
        return -1;
      }
      out.push_back({offsets_[i], ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                     static_cast<double>(ev.ts.tv_sec) + 1e-9 * static_cast<double>(ev.ts.tv_nsec)});
      ++n;
    }
    return n;
  }

  void close() override {
    for (gpiod_line* l : lines_) gpiod_line_release(l);
    lines_.clear();
    if (chip_) gpiod_chip_close(chip_);
    chip_ = nullptr;
  }
  [[nodiscard]] std::string error() const override { return std::strerror(errno_); }
  [[nodiscard]] std::string describe() const override { return "gpio " + chip_name_; }

 private:
  std::string chip_name_;
  std::vector<unsigned> offsets_;
  bool active_low_;
  std::string consumer_;
  gpiod_chip* chip_ = nullptr;
  std::vector<gpiod_line*> lines_;
  int errno_ = 0;
};

}  // namespace

std::unique_ptr<GpioSource> make_gpiod_source(const std::string& chip, std::vector<unsigned> lines,
                                              bool active_low, const std::string& consumer) {
  return std::make_unique<GpiodSource>(chip, std::move(lines), active_low, consumer);
}

}  // namespace walk::devices
