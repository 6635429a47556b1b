#pragma once
// What a walkd run did, written as summary.json when it ends (normally or on SIGTERM) so simulated runs
// can be checked by tests and compared between builds.
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace walk::kiosk {

struct Summary {
  static constexpr std::size_t kRoomSequenceKept = 256;  // the latest room changes; a kiosk runs for months

  std::string mode;        // "simulated" or "realtime"
  std::string stopped_by;  // "end", "signal", "window" or "next_building"
  std::string renderer;
  std::uint64_t frames = 0;        // steps of the loop
  std::uint64_t frames_drawn = 0;  // steps that drew a new picture (a converged still view draws none)
  double simulated_seconds = 0.0;  // time on the daemon's clock
  double wall_seconds = 0.0;       // whole loop
  double render_seconds = 0.0;     // wall time inside draw + present
  double fps = 0.0;                // frames_drawn / render_seconds
  std::vector<std::uint32_t> cells_visited;  // in first-visit order
  std::vector<std::string> rooms_visited;    // group names, first-visit order
  std::vector<std::string> room_sequence;  // room changes, from the start room; the latest kRoomSequenceKept
  std::uint64_t room_changes = 0;          // all of them, the start room counted
  double distance = 0.0;                   // metres walked
  std::uint64_t frames_saved = 0;          // PNGs written (encoded off the render thread)
  std::uint64_t frames_not_saved = 0;      // dropped by a full save queue or failed to write (logged)
  glm::dvec3 final_feet{0.0};              // world metres
  glm::dvec3 final_eye{0.0};
  double final_heading_deg = 0.0;
  std::string final_room;
  std::uint32_t final_cell = 0;
  std::uint64_t reloads = 0;  // SIGHUP config reloads applied
  std::uint64_t returns_to_start = 0;
  // Per device: "treadmill": "live", ... at the end, and how many frames each spent not live.
  std::vector<std::pair<std::string, std::string>> device_states;
  std::vector<std::pair<std::string, std::uint64_t>> device_faulty_frames;
  // Real-time runs with hardware devices: reading timestamp -> frame presented, seconds.
  double latency_p50 = 0.0, latency_p99 = 0.0, latency_max = 0.0;
  std::uint64_t latency_samples = 0;
};

[[nodiscard]] std::string summary_json(const Summary& summary);
// Writes `folder`/summary.json (creating the folder); throws walk::Error naming the path on failure.
void write_summary(const std::string& folder, const Summary& summary);

}  // namespace walk::kiosk
