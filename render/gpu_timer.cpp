#include "render/gpu_timer.hpp"

#include <cstring>

#include "render/gl_check.hpp"

namespace walk::render {

bool software_rasterizer() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!renderer) return true;  // cannot tell: the safe choice times whole frames
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer"})
    if (std::strstr(renderer, name)) return true;
  return false;
}

bool timer_queries_supported() {
  GLint bits = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
  return glGetError() == GL_NO_ERROR && bits > 0;
}

GpuTimer::GpuTimer() {
  glGenQueries(GLsizei(kInFlight), queries_.data());
  check_gl("creating timer queries");
}

GpuTimer::~GpuTimer() {
  if (open_) glEndQuery(GL_TIME_ELAPSED);
  glDeleteQueries(GLsizei(kInFlight), queries_.data());
}

void GpuTimer::begin() {
  if (pending_ == kInFlight) {  // the GPU is kInFlight frames behind: wait for the oldest, drop its time
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[oldest_], GL_QUERY_RESULT, &ns);
    oldest_ = (oldest_ + 1) % kInFlight;
    --pending_;
  }
  const std::size_t slot = (oldest_ + pending_) % kInFlight;
  begun_[slot] = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, queries_[slot]);
  open_ = true;
}

void GpuTimer::end(const Frame& frame) {
  glEndQuery(GL_TIME_ELAPSED);
  open_ = false;
  frames_[(oldest_ + pending_) % kInFlight] = frame;
  ++pending_;
}

std::optional<std::pair<GpuTimer::Frame, double>> GpuTimer::ready() {
  while (pending_) {
    GLint available = 0;
    glGetQueryObjectiv(queries_[oldest_], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) return std::nullopt;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[oldest_], GL_QUERY_RESULT, &ns);
    const double ms = double(ns) * 1e-6;
    const double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begun_[oldest_]).count();
    std::pair<Frame, double> out{frames_[oldest_], ms};
    oldest_ = (oldest_ + 1) % kInFlight;
    --pending_;
    if (ms <= wall_ms) return out;
    ++rejected_;
  }
  return std::nullopt;
}

}  // namespace walk::render
