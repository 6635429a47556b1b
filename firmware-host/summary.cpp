#include "firmware-host/summary.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.hpp"

namespace walk::kiosk {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

template <typename T, typename F>
std::string list(const std::vector<T>& items, F&& format) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + format(items[i]);
  return out + "]";
}

std::string vec(const glm::dvec3& v) {
  return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]";
}

}  // namespace

std::string summary_json(const Summary& s) {
  std::ostringstream o;
  o << "{\n"
    << "  \"mode\": " << quoted(s.mode) << ",\n"
    << "  \"stopped_by\": " << quoted(s.stopped_by) << ",\n"
    << "  \"renderer\": " << quoted(s.renderer) << ",\n"
    << "  \"frames\": " << s.frames << ",\n"
    << "  \"frames_drawn\": " << s.frames_drawn << ",\n"
    << "  \"simulated_seconds\": " << num(s.simulated_seconds) << ",\n"
    << "  \"wall_seconds\": " << num(s.wall_seconds) << ",\n"
    << "  \"render_seconds\": " << num(s.render_seconds) << ",\n"
    << "  \"fps\": " << num(s.fps) << ",\n"
    << "  \"cells_visited\": " << list(s.cells_visited, [](std::uint32_t c) { return std::to_string(c); })
    << ",\n"
    << "  \"rooms_visited\": " << list(s.rooms_visited, quoted) << ",\n"
    << "  \"room_sequence\": " << list(s.room_sequence, quoted) << ",\n"
    << "  \"distance_m\": " << num(s.distance) << ",\n"
    << "  \"frames_saved\": " << s.frames_saved << ",\n"
    << "  \"final_feet\": " << vec(s.final_feet) << ",\n"
    << "  \"final_eye\": " << vec(s.final_eye) << ",\n"
    << "  \"final_heading_deg\": " << num(s.final_heading_deg) << ",\n"
    << "  \"final_room\": " << quoted(s.final_room) << ",\n"
    << "  \"final_cell\": " << s.final_cell << ",\n"
    << "  \"reloads\": " << s.reloads << ",\n"
    << "  \"returns_to_start\": " << s.returns_to_start << ",\n"
    << "  \"devices\": {";
  for (std::size_t i = 0; i < s.device_states.size(); ++i)
    o << (i ? ", " : "") << quoted(s.device_states[i].first) << ": " << quoted(s.device_states[i].second);
  o << "},\n  \"device_faulty_frames\": {";
  for (std::size_t i = 0; i < s.device_faulty_frames.size(); ++i)
    o << (i ? ", " : "") << quoted(s.device_faulty_frames[i].first) << ": "
      << s.device_faulty_frames[i].second;
  o << "},\n"
    << "  \"latency_samples\": " << s.latency_samples << ",\n"
    << "  \"latency_p50_ms\": " << num(s.latency_p50 * 1e3) << ",\n"
    << "  \"latency_p99_ms\": " << num(s.latency_p99 * 1e3) << ",\n"
    << "  \"latency_max_ms\": " << num(s.latency_max * 1e3) << "\n"
    << "}\n";
  return o.str();
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
