#pragma once
// GPU time of a frame from GL timer queries (GL_TIME_ELAPSED, core in GL 3.3), read back a few frames later
// so the CPU never waits for the GPU: timing each frame with glFinish instead drains the pipeline, which on
// a hardware GPU costs the overlap of one frame's CPU work with the previous frame's drawing.
#include <glad/gl.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "render/frame_timing.hpp"

namespace walk::render {

// Whether the current context's driver rasterizes on the CPU (llvmpipe, softpipe, swrast). There the "GPU"
// is the CPU's own cores: vertex work runs in the draw call and rasterization after it, so a timer query
// misses part of the frame and glFinish costs no overlap worth keeping.
[[nodiscard]] bool software_rasterizer();
// Whether the context's timer queries count (GL_QUERY_COUNTER_BITS > 0).
[[nodiscard]] bool timer_queries_supported();

class GpuTimer {
 public:
  // What a timed frame was, handed back with its time so the governor learns for the right cell and level.
  struct Frame {
    bool moving = true;
    std::uint32_t cell = 0;
    std::uint8_t level = 0;
    double triangles = -1.0;
    int samples = 1;      // accumulation samples drawn in the frame
    double cpu_ms = 0.0;  // submission time on the CPU
  };
  static constexpr std::size_t kInFlight = 4;  // queries outstanding; a begin() beyond waits for the oldest

  GpuTimer();
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin();
  void end(const Frame& frame);
  // The oldest finished frame and its GPU milliseconds, if one is ready; never waits. A time longer than the
  // wall time since its begin() cannot be true (llvmpipe answers a query over a bare clear with its clock's
  // absolute value) and is dropped, counted in rejected().
  [[nodiscard]] std::optional<std::pair<Frame, double>> ready();
  [[nodiscard]] std::uint64_t rejected() const { return rejected_; }

 private:
  std::array<GLuint, kInFlight> queries_{};
  std::array<Frame, kInFlight> frames_{};
  std::array<std::chrono::steady_clock::time_point, kInFlight> begun_{};
  std::uint64_t rejected_ = 0;
  std::size_t oldest_ = 0, pending_ = 0;
  bool open_ = false;
};

}  // namespace walk::render
