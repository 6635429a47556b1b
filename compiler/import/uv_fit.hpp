#pragma once
// Texture coordinates given per corner (OBJ `vt`, glTF TEXCOORD_0) turned into a polygon's TextureMap.
#include <glm/vec2.hpp>
#include <optional>
#include <span>

#include "model/model.hpp"

namespace walk::compiler {

// The affine map over the corners' plane that best fits their coordinates (least squares: exact for a
// triangle, and for any polygon whose coordinates are affine, as planar mapping and most unwrapping give).
// Shifted by whole repeats so that the first corner's coordinates lie in [0, 1): the texture repeats, and
// float evaluation in the renderer keeps its precision. Empty for fewer than three corners, a polygon with
// no area, or corners that do not span the plane (all on one line).
[[nodiscard]] std::optional<model::TextureMap> fit_texture_map(std::span<const model::Vec3> corners,
                                                               std::span<const glm::dvec2> uvs);

}  // namespace walk::compiler
