#pragma once
// IES LM-63 photometric files (1986, 1991, 1995, 2002 and 2019 headers), type C photometry: the
// distribution of a luminaire as manufacturers publish it.
#include <string>
#include <string_view>

#include "model/intensity_distribution.hpp"

namespace walk::compiler {

// `path` names the file in messages. Throws walk::Error "path:line: what" for anything malformed.
[[nodiscard]] model::IntensityDistribution parse_ies(std::string_view text, const std::string& path);

}  // namespace walk::compiler
