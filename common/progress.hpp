#pragma once
// Progress of long work (solver rounds, cells, verification rows, benchmark frames), shown as a bar with rate
// and ETA when stderr is a terminal, and as a periodic one-line log (no control characters) when it is not or
// when running under systemd. Short work prints nothing: the first bar waits kBarDelay, the first log line
// kLogInterval. advance() is safe from any thread and costs one clock read and two atomics, so it may be
// called per item of a parallel loop.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace walk {

enum class ProgressStyle { Auto, Bar, Log, None };

// Process-wide style, set once from the command line (walk --progress). Auto resolves on first use.
void set_progress_style(ProgressStyle style);
ProgressStyle progress_style();
// "auto", "bar", "log" or "none"; false for anything else (out unchanged).
bool parse_progress_style(const std::string& text, ProgressStyle& out);

class Progress {
 public:
  // total = 0: the amount of work is not known in advance (no bar, no ETA unless set_fraction is used).
  Progress(std::string task, std::uint64_t total = 0, std::string unit = "");
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::uint64_t n = 1);
  // For work measured otherwise than by a count (the solver: how far the unshot power is on its way down to
  // the residual); fraction in [0, 1], detail shown after the rate.
  void set_fraction(double fraction, const std::string& detail = {});

  // The line as it would be shown now (for tests and the log form).
  [[nodiscard]] std::string line() const;

 private:
  void maybe_show();
  // Share of the work done, 0..1, from set_fraction or done/total; negative when neither is known.
  [[nodiscard]] double share(std::uint64_t done) const;
  using Clock = std::chrono::steady_clock;
  std::string task_, unit_;
  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<double> fraction_{-1.0};
  Clock::time_point start_;
  std::atomic<std::int64_t> next_show_ns_;
  mutable std::mutex mutex_;  // guards detail_ and the output
  std::string detail_;
  ProgressStyle style_;
  bool shown_ = false;
};

}  // namespace walk
