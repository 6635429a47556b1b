#pragma once
// Adaptive subdivision of diced meshes where direct light bends (Cohen, Greenberg, Immel & Brock 1986's
// adaptive subdivision, tested on edges): the display interpolates light linearly between vertices, so an
// edge whose midpoint's gathered direct light differs from the mean of its ends by more than the tolerance
// is split there, and its triangles with it, until every edge passes or reaches the shortest length. Light
// resolution then follows the light (shadow edges, the falloff next to a lamp), not the dicing grid. Edges
// crossing the outline of a panel hung parallel just in front of the surface (a ceiling's lamp) are split
// too, whatever the direct light: the panel hides the room from the surface there (light_refinement.cpp).
#include <cstddef>
#include <vector>

#include "compiler/geometry/mesher.hpp"
#include "compiler/radiosity/sparse_light.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct LightRefinementOptions {
  // Relative to the RMS direct irradiance over the meshes' vertices: the interpolation error allowed at
  // an edge's midpoint (the scene's target_error).
  double tolerance = 0.05;
  double min_edge = 0.02;  // metres: edges this short are never split
  int max_levels = 4;      // each level halves the edges it splits
  int samples_per_luminaire = 8;
  unsigned threads = 2;
};

struct LightRefinementStats {
  std::size_t edges_tested = 0;
  std::size_t edges_split = 0;
  std::size_t outline_splits = 0;  // of which for crossing the outline of a panel hung close in front
  std::size_t triangles_added = 0;
  int levels = 0;
  double shadow_rays = 0.0;
  std::size_t circuits = 0;  // of the gathered light handed back: the luminaires' largest circuit + 1
};

// Refines `meshes[i]` for i where `lit[i]` (panels and the like are left alone); `occluders` cast the
// shadows. Orientation is kept; a split triangle keeps its place with one piece, the others go to the end.
// `direct` (optional) receives, per mesh, the direct light gathered at each vertex of the refined mesh,
// a row per vertex, for a surface of reflectance 1 (no rows for meshes not lit), so the light stage shows
// the very values the edges were tested with instead of gathering them again.
LightRefinementStats refine_by_direct_light(std::vector<PolygonMesh>& meshes, const std::vector<bool>& lit,
                                            const std::vector<model::Luminaire>& luminaires,
                                            const TriangleBvh& occluders,
                                            const LightRefinementOptions& options,
                                            std::vector<SparseLight>* direct = nullptr);

}  // namespace walk::compiler
