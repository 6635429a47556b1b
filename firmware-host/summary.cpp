#include "firmware-host/summary.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "model/error.hpp"

namespace walk::kiosk {

// nlohmann-json, keys in the order written: readers diffing two summaries see the same layout, and a value
// that is not a number (a NaN from a run that drew nothing) is written as null, never as `nan`.
std::string summary_json(const Summary& s) {
  using Json = nlohmann::ordered_json;
  auto vec = [](const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); };
  Json j;
  j["mode"] = s.mode;
  j["stopped_by"] = s.stopped_by;
  j["renderer"] = s.renderer;
  j["frames"] = s.frames;
  j["frames_drawn"] = s.frames_drawn;
  j["simulated_seconds"] = s.simulated_seconds;
  j["wall_seconds"] = s.wall_seconds;
  j["render_seconds"] = s.render_seconds;
  j["fps"] = s.fps;
  j["cells_visited"] = s.cells_visited;
  j["rooms_visited"] = s.rooms_visited;
  j["room_sequence"] = s.room_sequence;
  j["room_changes"] = s.room_changes;
  j["distance_m"] = s.distance;
  j["frames_saved"] = s.frames_saved;
  j["frames_not_saved"] = s.frames_not_saved;
  j["final_feet"] = vec(s.final_feet);
  j["final_eye"] = vec(s.final_eye);
  j["final_heading_deg"] = s.final_heading_deg;
  j["final_room"] = s.final_room;
  j["final_cell"] = s.final_cell;
  j["reloads"] = s.reloads;
  j["returns_to_start"] = s.returns_to_start;
  j["devices"] = Json::object();
  for (const auto& [name, state] : s.device_states) j["devices"][name] = state;
  j["device_faulty_frames"] = Json::object();
  for (const auto& [name, frames] : s.device_faulty_frames) j["device_faulty_frames"][name] = frames;
  j["latency_samples"] = s.latency_samples;
  j["latency_p50_ms"] = s.latency_p50 * 1e3;
  j["latency_p99_ms"] = s.latency_p99 * 1e3;
  j["latency_max_ms"] = s.latency_max * 1e3;
  // Replace: invalid UTF-8 in a room name read from a bundle must not stop the summary being written.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_summary(const std::string& folder, const Summary& summary) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  const std::string path = (std::filesystem::path(folder) / "summary.json").string();
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << summary_json(summary);
    if (!out) throw Error(located(path, 0, "cannot write the run summary", "check the output folder"));
  }
  std::filesystem::rename(tmp, path, ec);  // readers never see half a summary
  if (ec) throw Error(located(path, 0, "cannot write the run summary: " + ec.message()));
}

}  // namespace walk::kiosk
