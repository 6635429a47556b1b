#include "model/error.hpp"

namespace walk {

std::string located(const std::string& file, std::size_t line, const std::string& what,
                    const std::string& hint) {
  std::string out = file;
  if (line > 0) out += ":" + std::to_string(line);
  out += ": " + what;
  if (!hint.empty()) out += " (" + hint + ")";
  return out;
}

}  // namespace walk
