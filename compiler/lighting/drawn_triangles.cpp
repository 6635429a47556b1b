#include "compiler/lighting/drawn_triangles.hpp"

namespace walk::compiler {

std::vector<TriangleCorners> drawn_triangles(const model::Bundle& b, bool with_panels) {
  std::vector<TriangleCorners> out;
  const auto idx = b.indices();
  for (const auto& p : b.polygons()) {
    const auto role = static_cast<model::Role>(p.role);
    if (role != model::Role::Opaque && role != model::Role::Glass &&
        !(with_panels && role == model::Role::Luminaire))
      continue;
    for (std::uint32_t k = p.first_index; k + 2 < p.first_index + p.index_count; k += 3)
      out.push_back({idx[k], idx[k + 1], idx[k + 2]});
  }
  return out;
}

}  // namespace walk::compiler
