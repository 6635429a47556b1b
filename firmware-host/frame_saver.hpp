#pragma once
// Saves captured frames as PNG on a thread of its own: encoding a 1080p frame takes tens of milliseconds,
// which on the render thread would drop frames of the walk. The queue is bounded (a slow disk drops saves,
// counted and logged once per episode, rather than growing memory) and each file appears whole or not at all
// (written beside the target, then renamed).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "render/renderer.hpp"

namespace walk::kiosk {

class FrameSaver {
 public:
  static constexpr std::size_t kMaxQueued = 2;  // frames waiting to be encoded; at 1080p about 16 MB

  FrameSaver();
  ~FrameSaver();  // finishes the queued saves
  FrameSaver(const FrameSaver&) = delete;
  FrameSaver& operator=(const FrameSaver&) = delete;

  // What save() does when kMaxQueued saves are waiting: a real-time kiosk drops the frame (counted), a
  // simulated run, which has no deadline and must be deterministic, waits for room.
  enum class WhenFull : std::uint8_t { Drop, Wait };
  // Queues `image` for `path`; false (and counted as dropped) when the queue is full and `full` is Drop.
  bool save(std::string path, render::Image image, WhenFull full = WhenFull::Drop);
  void flush();  // returns once every queued save has been written or has failed

  [[nodiscard]] std::uint64_t written() const;
  [[nodiscard]] std::uint64_t dropped() const;
  [[nodiscard]] std::uint64_t failed() const;

 private:
  void work();

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_, room_;
  std::deque<std::pair<std::string, render::Image>> queue_;
  bool busy_ = false, stopping_ = false, dropping_ = false;
  std::uint64_t written_ = 0, dropped_ = 0, failed_ = 0;
  std::thread thread_;
};

}  // namespace walk::kiosk
