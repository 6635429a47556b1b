#pragma once
// Intel Embree 3 behind the RayCaster interface: the reference to compare against and an alternative backend.
// Compiled in only with WALK_WITH_EMBREE (cmake/Embree.cmake); the core never needs it.
// Embree works in single precision, so triangles and rays are moved to the whole-metre local frame first.
#include <memory>
#include <span>

#include "compiler/raycast/ray_caster.hpp"

namespace walk::compiler {

[[nodiscard]] bool embree_available();
// Throws walk::Error when Embree is not compiled in or fails to build the scene.
// `exact` ("embree-exact"): each hit Embree finds counts only where the ray meets the triangle's plane
// within (tmin, tmax) in double, and reports that t, so the self-hit policy holds as in the double-precision
// casters; plain Embree reports the surface a ray leaves (its float origin lies micrometres off it).
[[nodiscard]] std::unique_ptr<RayCaster> make_embree_caster(std::span<const Triangle> triangles,
                                                            bool exact = false);

}  // namespace walk::compiler
