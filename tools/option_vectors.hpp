#pragma once
// Command-line values the tools share: three comma-separated numbers (CLI11 reads them as a list) as a
// vector, with an error naming the option when there are not three; a frame size WIDTHxHEIGHT.
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "model/error.hpp"
#include "model/model.hpp"

namespace walk::tools {

// `option` without its dashes; `meaning` says in what frame or unit, e.g. "in local metres".
[[nodiscard]] inline model::Vec3 option_vec3(const std::vector<double>& v, const std::string& option,
                                             const std::string& meaning = {}) {
  if (v.size() != 3)
    throw Error("--" + option + " needs three numbers x,y,z" + (meaning.empty() ? "" : " " + meaning) +
                ", got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

// "WIDTHxHEIGHT" as (width, height), both positive and, if `max_side` > 0, at most it; nullopt otherwise
// (each command words its own error).
[[nodiscard]] inline std::optional<std::pair<int, int>> parse_frame_size(const std::string& text,
                                                                         int max_side = 0) {
  int width = 0, height = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || x != 'x' || width <= 0 || height <= 0) return std::nullopt;
  if (max_side > 0 && (width > max_side || height > max_side)) return std::nullopt;
  return std::pair{width, height};
}

}  // namespace walk::tools
