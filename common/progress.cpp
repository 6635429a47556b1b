#include "common/progress.hpp"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace walk {
namespace {

// A bar for work that ends within this is never drawn (no flicker on small models).
constexpr auto kBarDelay = std::chrono::milliseconds(300);
// A terminal redraws at most this often: smooth to the eye, negligible for the work.
constexpr auto kBarInterval = std::chrono::milliseconds(100);
// Logs (journal, files, CI) get one line this often: a minutes-long compile shows it is alive without
// flooding the journal.
constexpr auto kLogInterval = std::chrono::seconds(5);
constexpr int kBarWidth = 24;  // characters of the bar itself

std::atomic<ProgressStyle> g_style{ProgressStyle::Auto};

ProgressStyle resolve_auto() {
  // systemd sets INVOCATION_ID for units and JOURNAL_STREAM when stderr is the journal: log lines there.
  if (std::getenv("INVOCATION_ID") || std::getenv("JOURNAL_STREAM")) return ProgressStyle::Log;
  const char* term = std::getenv("TERM");
  if (!isatty(STDERR_FILENO) || !term || std::string(term) == "dumb") return ProgressStyle::Log;
  return ProgressStyle::Bar;
}

// The terminal's width: a bar longer than the line would wrap, and '\r' returns only to the last row.
std::size_t terminal_columns() {
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{}:{:02}", s / 60, s % 60);
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

}  // namespace

void set_progress_style(ProgressStyle style) {
  g_style = style == ProgressStyle::Auto ? resolve_auto() : style;
}

ProgressStyle progress_style() {
  ProgressStyle s = g_style.load();
  if (s == ProgressStyle::Auto) {
    s = resolve_auto();
    g_style = s;
  }
  return s;
}

bool parse_progress_style(const std::string& text, ProgressStyle& out) {
  if (text == "auto")
    out = ProgressStyle::Auto;
  else if (text == "bar")
    out = ProgressStyle::Bar;
  else if (text == "log")
    out = ProgressStyle::Log;
  else if (text == "none")
    out = ProgressStyle::None;
  else
    return false;
  return true;
}

Progress::Progress(std::string task, std::uint64_t total, std::string unit)
    : task_(std::move(task)),
      unit_(std::move(unit)),
      total_(total),
      start_(Clock::now()),
      style_(progress_style()) {
  const auto first = style_ == ProgressStyle::Bar ? std::chrono::duration_cast<Clock::duration>(kBarDelay)
                                                  : std::chrono::duration_cast<Clock::duration>(kLogInterval);
  next_show_ns_ = (start_ + first).time_since_epoch().count();
}

Progress::~Progress() {
  std::lock_guard lock(mutex_);
  if (style_ == ProgressStyle::Bar && shown_) {
    std::fputs("\r\033[K", stderr);  // the stage's own result line follows on a clean line
    std::fflush(stderr);
  }
}

void Progress::advance(std::uint64_t n) {
  done_.fetch_add(n, std::memory_order_relaxed);
  maybe_show();
}

void Progress::set_fraction(double fraction, const std::string& detail) {
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  {
    std::lock_guard lock(mutex_);
    detail_ = detail;
  }
  maybe_show();
}

double Progress::share(std::uint64_t done) const {
  const double fraction = fraction_.load();
  if (fraction < 0 && total_ > 0) return std::min(1.0, double(done) / double(total_));
  return fraction;
}

std::string Progress::line() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const std::uint64_t done = done_.load(std::memory_order_relaxed);
  const double fraction = share(done);
  std::string text = task_ + ":";
  if (fraction >= 0) text += fmt::format(" {:3.0f}%,", 100.0 * fraction);
  text += total_ > 0 ? fmt::format(" {}/{} {}", done, total_, unit_) : fmt::format(" {} {}", done, unit_);
  if (elapsed > 0 && done > 0) text += fmt::format(", {:.3g} {}/s", done / elapsed, unit_);
  if (fraction > 0.01 && fraction < 1.0)
    text += ", ETA " + duration_text(elapsed * (1.0 - fraction) / fraction);
  text += ", " + duration_text(elapsed) + " so far";
  std::lock_guard lock(mutex_);
  if (!detail_.empty()) text += ", " + detail_;
  return text;
}

void Progress::maybe_show() {
  if (style_ == ProgressStyle::None) return;
  const auto now = Clock::now().time_since_epoch().count();
  auto next = next_show_ns_.load(std::memory_order_relaxed);
  if (now < next) return;
  const auto interval = style_ == ProgressStyle::Bar
                            ? std::chrono::duration_cast<Clock::duration>(kBarInterval).count()
                            : std::chrono::duration_cast<Clock::duration>(kLogInterval).count();
  // One thread wins the slot and prints; the others go back to work at once.
  if (!next_show_ns_.compare_exchange_strong(next, now + interval)) return;
  const std::string text = line();
  if (style_ == ProgressStyle::Log) {
    // Straight to stderr, not through the logger: it shows at the default log level, one whole line.
    std::lock_guard lock(mutex_);
    std::fprintf(stderr, "progress %s\n", text.c_str());
    std::fflush(stderr);
    return;
  }
  const double fraction = share(done_.load(std::memory_order_relaxed));
  std::string bar;
  if (fraction >= 0) {
    const int filled = static_cast<int>(std::lround(fraction * kBarWidth));
    bar = "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '-') + "] ";
  }
  std::string shown = bar + text;
  if (const std::size_t columns = terminal_columns(); shown.size() >= columns) shown.resize(columns - 1);
  std::lock_guard lock(mutex_);
  std::fprintf(stderr, "\r%s\033[K", shown.c_str());
  std::fflush(stderr);
  shown_ = true;
}

}  // namespace walk
