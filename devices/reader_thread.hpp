#pragma once
// Runs a backend's step function on its own thread until destroyed, so a slow or silent device never blocks
// the render loop. Each step must return within its own bounded timeout (a read or wait with a timeout).
#include <atomic>
#include <functional>
#include <thread>

namespace walk::devices {

class ReaderThread {
 public:
  ReaderThread() = default;
  ReaderThread(const ReaderThread&) = delete;
  ReaderThread& operator=(const ReaderThread&) = delete;
  ~ReaderThread() { stop(); }

  void start(std::function<void()> step) {
    stop();
    running_ = true;
    thread_ = std::thread([this, step = std::move(step)] {
      while (running_.load(std::memory_order_relaxed)) step();
    });
  }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  [[nodiscard]] bool running() const { return running_; }

 private:
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace walk::devices
