// kiosk_latency: a simulated real-time kiosk run measuring device-to-frame latency, printed as CSV.
//   kiosk_latency [--bundle house.walk] [--seconds 10] [--hz 60] [--width 640] [--height 360] [--backend
//   osmesa] [--stereo off|side_by_side] [--screens 1..3]
// walkd's Daemon runs in real time on the GL renderer with: a HID treadmill and a HID head tracker fed raw
// reports at 250 Hz through the HidSource seam (timestamped on arrival by the real reader threads), and a
// Modbus TCP dimmer panel polled at 50 Hz against the panel simulator on 127.0.0.1, whose registers change
// every 0.2 s. The head tracker reports yaw and position (a sway), so in screen mode (the default) every
// frame's view moves with the head. --stereo and --screens draw two eyes and/or several screens of one
// spanning output (three: a front wall and two side walls angled in), for their frame-time cost.
// Latency = present() of the frame that used a reading - the reading's timestamp. Without
// --bundle, the sample house is compiled first (config/scenes/house.toml).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include "compiler/pipeline.hpp"
#include "devices/hid/hid_device.hpp"
#include "devices/sim/panel_simulator.hpp"
#include "firmware-host/daemon.hpp"

namespace {

using namespace walk;

// A HID device that produces `rate` reports per second from a thread; read() blocks like hid_read_timeout.
class FeedHid final : public devices::HidSource {
 public:
  FeedHid(double rate, std::function<std::vector<std::uint8_t>(int)> make)
      : rate_(rate), make_(std::move(make)) {}
  ~FeedHid() override { close(); }
  std::string open() override {
    running_ = true;
    thread_ = std::thread([this] {
      auto next = std::chrono::steady_clock::now();
      for (int i = 0; running_; ++i) {
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(1.0 / rate_));
        std::this_thread::sleep_until(next);
        std::lock_guard lock(mutex_);
        queue_.push_back(make_(i));
        cv_.notify_one();
      }
    });
    return {};
  }
  int read(std::span<std::uint8_t> buf, int timeout_ms) override {
    std::unique_lock lock(mutex_);
    if (!cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms), [&] { return !queue_.empty(); })) return 0;
    const auto r = std::move(queue_.front());
    queue_.pop_front();
    const auto n = std::min(buf.size(), r.size());
    std::memcpy(buf.data(), r.data(), n);
    return static_cast<int>(n);
  }
  void close() override {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  std::string error() const override { return "none"; }
  std::string describe() const override { return "bench feed"; }

 private:
  double rate_;
  std::function<std::vector<std::uint8_t>(int)> make_;
  std::atomic<bool> running_{false};
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::vector<std::uint8_t>> queue_;
};

struct Stats {
  std::size_t n = 0;
  double p50 = 0, p99 = 0, max = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.n = v.size();
  s.p50 = v[(v.size() - 1) / 2] * 1e3;
  s.p99 = v[static_cast<std::size_t>(0.99 * static_cast<double>(v.size() - 1))] * 1e3;
  s.max = v.back() * 1e3;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string bundle_path, backend = "osmesa", stereo = "off";
  int screens = 1;
  double seconds = 10, hz = 60;
  int width = 640, height = 360;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--bundle")
      bundle_path = v;
    else if (k == "--seconds")
      seconds = std::stod(v);
    else if (k == "--hz")
      hz = std::stod(v);
    else if (k == "--width")
      width = std::stoi(v);
    else if (k == "--height")
      height = std::stoi(v);
    else if (k == "--backend")
      backend = v;
    else if (k == "--stereo")
      stereo = v;
    else if (k == "--screens")
      screens = std::clamp(std::stoi(v), 1, 3);
    else {
      std::fprintf(stderr, "kiosk_latency: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  spdlog::set_level(spdlog::level::warn);
  try {
    if (bundle_path.empty()) {
      bundle_path = (std::filesystem::temp_directory_path() / "kiosk_latency_house.walk").string();
      compiler::compile_to_file(WALK_SOURCE_DIR "/config/scenes/house.toml", bundle_path, true);
    }
    auto sim = devices::PanelSimulator::tcp("127.0.0.1", 0, 4);
    kiosk::KioskConfig config = kiosk::load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/demo.toml");
    config.bundle = bundle_path;
    config.display.backend = backend;
    config.display.width = width;
    config.display.height = height;
    config.simulation.seconds = 0;  // real time
    config.simulation.frame_rate = hz;
    config.output.folder = (std::filesystem::temp_directory_path() / "kiosk_latency_out").string();
    config.output.png_every = 0;
    config.devices = {};
    config.display.stereo = stereo;
    if (screens > 1) {
      // Walls 1.6 x 0.9 m, 1 m ahead, the side ones turned 30 degrees in (tracker frame, metres).
      const double z0 = 1.15, z1 = 2.05;
      config.display.screens = {{{-0.8, 1.0, z0}, {0.8, 1.0, z0}, {-0.8, 1.0, z1}},
                                {{-2.186, 0.2, z0}, {-0.8, 1.0, z0}, {-2.186, 0.2, z1}},
                                {{0.8, 1.0, z0}, {2.186, 0.2, z0}, {0.8, 1.0, z1}}};
      config.display.screens.resize(std::size_t(screens));
      if (screens == 3)
        std::swap(config.display.screens[0], config.display.screens[1]);  // left, front, right
    }

    kiosk::DeviceSet set;
    devices::HidReportLayout tl;  // report 1: speed u16 mm/s
    tl.report_id = 1;
    tl.length = 3;
    tl.fields = {{"speed", 1, 2, false, false, 0.001, 0.0, 0.0, 5.0}};
    auto treadmill_reader = std::make_unique<devices::HidReader>(
        "treadmill (bench)",
        std::make_unique<FeedHid>(250.0,
                                  [](int) {
                                    return std::vector<std::uint8_t>{1, 0xf4, 0x01};
                                  }),
        tl, devices::FaultPolicy{});
    treadmill_reader->start(50);
    set.treadmill = std::make_unique<devices::HidTreadmill>(std::move(treadmill_reader));
    devices::HidReportLayout hl;  // unnumbered: yaw s16 in milliradians, then x, y, z s16 in millimetres
    hl.length = 8;
    hl.fields = {{"yaw", 0, 2, true, false, 0.001, 0.0, -3.2, 3.2},
                 {"x", 2, 2, true, false, 0.001, 0.0, -0.5, 0.5},
                 {"y", 4, 2, true, false, 0.001, 0.0, -0.5, 0.5},
                 {"z", 6, 2, true, false, 0.001, 0.0, -0.5, 0.5}};
    auto head_reader = std::make_unique<devices::HidReader>(
        "head tracker (bench)",
        std::make_unique<FeedHid>(250.0,
                                  [](int i) {
                                    // Yaw sweeps within the dead zone; the head sways 4 cm at 0.9 Hz.
                                    const auto yaw = static_cast<std::int16_t>((i % 500) - 250);
                                    const auto x = static_cast<std::int16_t>(40.0 * std::sin(i * 0.0226));
                                    const auto z = static_cast<std::int16_t>(15.0 * std::sin(i * 0.0452));
                                    std::vector<std::uint8_t> r;
                                    for (const std::int16_t v : {yaw, x, std::int16_t(0), z}) {
                                      r.push_back(static_cast<std::uint8_t>(v & 0xff));
                                      r.push_back(static_cast<std::uint8_t>((v >> 8) & 0xff));
                                    }
                                    return r;
                                  }),
        hl, devices::FaultPolicy{});
    head_reader->start(50);
    set.head_tracker = std::make_unique<devices::HidHeadTracker>(std::move(head_reader));
    devices::ModbusPanelConfig mc;
    mc.port = sim->port();
    mc.registers = {0, 1, 2, 3};
    mc.poll_hz = 50;
    auto panel = std::make_unique<devices::ModbusDimmerPanel>(mc);
    panel->start();
    auto* modbus = panel.get();
    set.dimmer_panel = std::move(panel);

    const auto bundle = model::Bundle::open(bundle_path);
    auto renderer = kiosk::make_gl_renderer(*bundle, config.display);
    kiosk::Daemon daemon(config, *bundle, *renderer, std::move(set));
    std::atomic<bool> stop{false};
    std::thread timer([&] {
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
      for (int i = 0; std::chrono::steady_clock::now() < end; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        for (int r = 0; r < 4; ++r)
          sim->set_register(r, static_cast<std::uint16_t>((i * 37 + r * 250) % 1001));
      }
      stop = true;
    });
    const kiosk::Summary s = daemon.run(stop);
    timer.join();

    std::printf("metric,samples,p50_ms,p99_ms,max_ms\n");
    const char* names[3] = {"reading_to_frame_treadmill_hid250", "reading_to_frame_head_hid250",
                            "reading_to_frame_panel_modbus50"};
    // The daemon keeps latencies in bounded histograms (quantiles within about 2.3 %), as a kiosk does.
    kiosk::LatencyHistogram all;
    auto print_row = [](const char* name, const kiosk::LatencyHistogram& h) {
      std::printf("%s,%llu,%.2f,%.2f,%.2f\n", name, static_cast<unsigned long long>(h.count()),
                  h.quantile(0.5) * 1e3, h.quantile(0.99) * 1e3, h.max() * 1e3);
    };
    for (std::size_t role = 0; role < 3; ++role) {
      all.merge(daemon.latencies(role));
      print_row(names[role], daemon.latencies(role));
    }
    print_row("reading_to_frame_all", all);
    const Stats rt = stats(modbus->round_trips());
    std::printf("modbus_tcp_poll_round_trip,%zu,%.3f,%.3f,%.3f\n", rt.n, rt.p50, rt.p99, rt.max);
    std::printf(
        "# %s %dx%d at %g Hz for %g s, %s mode, stereo %s, %d screen(s): %llu frames, %.1f fps inside "
        "draw+present (%.2f ms a frame), renderer %s\n",
        bundle_path.c_str(), width, height, hz, seconds, config.display.mode.c_str(), stereo.c_str(), screens,
        static_cast<unsigned long long>(s.frames), s.fps, 1e3 / std::max(s.fps, 1e-9), s.renderer.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kiosk_latency: %s\n", e.what());
    return 1;
  }
  return 0;
}
