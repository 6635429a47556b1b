#pragma once
// The bundle's albedo maps: the textures the drawn polygons use (TEXR, TEXL) and each polygon's texture
// coordinates (PTEX). A scene with no textured polygon gets none of these sections.
#include <span>

#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// `polygons[i]` is the model polygon bundle polygon i was made from (luminaire panels included). Appends only
// the textures some polygon uses, in order of first use.
void add_polygon_textures(const model::Model& model, std::span<const model::Polygon* const> polygons,
                          model::BundleContents& out);

}  // namespace walk::compiler
