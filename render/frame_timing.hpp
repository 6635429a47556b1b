#pragma once
// How the renderer times its frames for the governor. GL-free, so config readers (and their fuzzers) can
// check the name without linking the renderer.
#include <cstdint>
#include <optional>
#include <string_view>

namespace walk::render {

enum class FrameTiming : std::uint8_t {
  Auto,     // Queries on hardware drivers, Finish on software rasterizers
  Finish,   // glFinish, then the CPU clock: the whole frame, at the cost of a drained pipeline
  Queries,  // timer queries, read frames later; a frame counts max(CPU submission time, GPU time)
};

inline constexpr std::string_view kFrameTimingNames = "auto, finish or queries";

[[nodiscard]] inline std::optional<FrameTiming> parse_frame_timing(std::string_view name) {
  if (name == "auto") return FrameTiming::Auto;
  if (name == "finish") return FrameTiming::Finish;
  if (name == "queries") return FrameTiming::Queries;
  return std::nullopt;
}

}  // namespace walk::render
