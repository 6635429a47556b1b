#pragma once
// Recursive bilinear subdivision (the paper's fourth refinement step). Radiosity over a quad patch is the
// bilinear blend of its corners; two Gouraud triangles miss it by the quad's twist, |c0 - c1 + c2 - c3| / 4
// at the centre, whichever diagonal is drawn. Quads whose twist exceeds a threshold are split into four
// bilinear sub-quads, again and again (each split quarters the twist) until it is below the threshold or a
// depth limit is reached. The result is drawn in place of those quads. Pure CPU.
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"
#include "render/diagonals.hpp"

namespace walk::render {

// A triangle corner with its final (already mixed) linear radiosity.
// `polygon` lets an albedo map follow a subdivided quad; kNoPolygon (markers drawn over the scene) has none.
inline constexpr std::uint32_t kNoPolygon = UINT32_MAX;
struct ShadedVertex {
  glm::vec3 position;
  glm::vec3 radiosity;
  std::uint32_t polygon = kNoPolygon;
};

struct Subdivision {
  std::vector<ShadedVertex> triangles;      // three per triangle, counter-clockwise
  std::vector<std::size_t> replaced_quads;  // indices into the quads given
};

// Twist of the quad's corner colours: the largest channel of |c0 - c1 + c2 - c3| / 4.
[[nodiscard]] float quad_twist(const glm::vec3 c[4]);

// `radiosity`: per vertex, as displayed (ambient and the dimmer mix included). Quads with twist above
// `threshold` (same unit) are subdivided at most `max_depth` times.
[[nodiscard]] Subdivision subdivide(std::span<const Quad> quads,
                                    std::span<const model::VertexRecord> vertices,
                                    std::span<const glm::vec3> radiosity, float threshold, int max_depth);

}  // namespace walk::render
