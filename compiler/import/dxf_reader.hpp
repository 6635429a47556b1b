#pragma once
// DXF import. Reads 3DFACE entities (triangles and quads) with their layer, ACI colour and the EnergyPlus
// "ZONE:SURFACE" 999 comment as the face name; layers become model groups. Throws walk::Error naming the file
// and the line of the offending group code for a truncated file, a non-numeric value or an empty model.
#include <string>

#include "model/model.hpp"

namespace walk::compiler {

struct DxfOptions {
  double unit_scale = 1.0;  // metres per drawing unit
};

[[nodiscard]] model::Model read_dxf(const std::string& path, const DxfOptions& options = {});

}  // namespace walk::compiler
