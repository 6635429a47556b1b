#pragma once
// Three comma-separated numbers of a command-line option (CLI11 reads them as a list) as a vector, with an
// error naming the option when there are not three.
#include <string>
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

}  // namespace walk::tools
