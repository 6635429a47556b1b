#include "compiler/scene/units.hpp"

#include <array>
#include <utility>

namespace walk::compiler {
namespace {
constexpr std::array<std::pair<const char*, double>, 9> kUnits{{{"m", 1.0},
                                                                {"metre", 1.0},
                                                                {"meter", 1.0},
                                                                {"cm", 0.01},
                                                                {"mm", 0.001},
                                                                {"in", 0.0254},
                                                                {"inch", 0.0254},
                                                                {"ft", 0.3048},
                                                                {"quake", 0.0254}}};
}  // namespace

std::optional<double> metres_per_unit(const std::string& name) {
  for (const auto& [unit, metres] : kUnits)
    if (name == unit) return metres;
  return std::nullopt;
}

const char* known_units() {
  return "m, cm, mm, in, ft, quake";
}

}  // namespace walk::compiler
