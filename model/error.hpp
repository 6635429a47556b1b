#pragma once
// One exception type for bad input anywhere in the pipeline. The message always names where the problem is
// (file and line, TOML key, bundle section, device) and what the user can do about it.
#include <stdexcept>
#include <string>

namespace walk {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// "file:line: what. hint" — line 0 means the location is the file as a whole.
[[nodiscard]] std::string located(const std::string& file, std::size_t line, const std::string& what,
                                  const std::string& hint = {});

}  // namespace walk
