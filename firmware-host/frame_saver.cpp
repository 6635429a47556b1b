#include "firmware-host/frame_saver.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>

namespace walk::kiosk {

FrameSaver::FrameSaver() : thread_([this] { work(); }) {}

FrameSaver::~FrameSaver() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

bool FrameSaver::save(std::string path, render::Image image, WhenFull full) {
  {
    std::unique_lock lock(mutex_);
    if (full == WhenFull::Wait) room_.wait(lock, [this] { return queue_.size() < kMaxQueued; });
    if (queue_.size() >= kMaxQueued) {
      ++dropped_;
      if (!dropping_)
        spdlog::warn(
            "{}: not saved, {} earlier frames are still being written (a slow disk?); saves are "
            "dropped until the queue drains",
            path, queue_.size());
      dropping_ = true;
      return false;
    }
    dropping_ = false;
    queue_.emplace_back(std::move(path), std::move(image));
  }
  wake_.notify_one();
  return true;
}

void FrameSaver::flush() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

void FrameSaver::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, nothing left
    auto [path, image] = std::move(queue_.front());
    queue_.pop_front();
    room_.notify_all();
    busy_ = true;
    lock.unlock();
    bool ok = true;
    try {
      const std::string part = path + ".part";
      render::write_png(part, image);
      std::filesystem::rename(part, path);
    } catch (const std::exception& e) {
      ok = false;
      std::error_code ec;
      std::filesystem::remove(path + ".part", ec);
      spdlog::error("frame not saved: {}", e.what());
    }
    lock.lock();
    busy_ = false;
    ++(ok ? written_ : failed_);
    if (queue_.empty()) idle_.notify_all();
  }
}

std::uint64_t FrameSaver::written() const {
  std::lock_guard lock(mutex_);
  return written_;
}
std::uint64_t FrameSaver::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}
std::uint64_t FrameSaver::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

}  // namespace walk::kiosk
