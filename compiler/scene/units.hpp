#pragma once
// Length units accepted at the config boundary; everything inside is metres.
#include <optional>
#include <string>

namespace walk::compiler {

// Metres per unit for "m", "cm", "mm", "in", "ft", "quake" (1 inch); nothing for an unknown name.
[[nodiscard]] std::optional<double> metres_per_unit(const std::string& name);
[[nodiscard]] const char* known_units();

}  // namespace walk::compiler
