#include "compiler/photometry/photometry_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compiler/photometry/eulumdat_reader.hpp"
#include "compiler/photometry/ies_reader.hpp"
#include "model/error.hpp"

namespace walk::compiler {

model::IntensityDistribution read_photometry_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".ies" && ext != ".ldt")
    throw Error(located(path, 0, "unknown photometric file type '" + ext + "'",
                        "give an IES LM-63 (.ies) or EULUMDAT (.ldt) file"));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(located(path, 0, "cannot open the photometric file", "check the path in the scene"));
  std::stringstream buffer;
  buffer << f.rdbuf();
  const std::string text = buffer.str();
  return ext == ".ies" ? parse_ies(text, path) : parse_eulumdat(text, path);
}

}  // namespace walk::compiler
