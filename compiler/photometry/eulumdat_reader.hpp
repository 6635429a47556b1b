#pragma once
// EULUMDAT (.ldt) photometric files, the European counterpart of IES LM-63: one field per line.
#include <string>
#include <string_view>

#include "model/intensity_distribution.hpp"

namespace walk::compiler {

// `path` names the file in messages. Throws walk::Error "path:line: what" for anything malformed.
[[nodiscard]] model::IntensityDistribution parse_eulumdat(std::string_view text, const std::string& path);

}  // namespace walk::compiler
