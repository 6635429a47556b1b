#pragma once
// The one entry point of the photometry folder: reads a luminaire's intensity distribution from an IES
// LM-63 (.ies) or EULUMDAT (.ldt) file, chosen by extension.
#include <string>

#include "model/intensity_distribution.hpp"

namespace walk::compiler {

// Throws walk::Error naming the file (and line) for an unreadable, unknown or malformed file.
[[nodiscard]] model::IntensityDistribution read_photometry_file(const std::string& path);

}  // namespace walk::compiler
