#pragma once
// T-junction repair across polygon meshes. Each polygon is diced on its own, so where two polygons abut, a
// vertex of one lies on an edge of the other without being a vertex of it. In double precision the seam is
// closed; once the bundle stores float coordinates, a vertex on a slanted edge is rounded off the line and
// leaves a crack of micrometres that rays (and the GPU, as sparkle pixels) can pass through. Inserting every
// such vertex into the edge it lies on makes both sides of a seam the same chain of identical vertices, which
// float rounding cannot open, because a watertight triangle test never passes between two triangles that
// share an edge.
#include <cstddef>
#include <vector>

#include "compiler/geometry/mesher.hpp"

namespace walk::compiler {

// Double-precision noise of diced coordinates (about 1e-12 m in a 10 km model; metres). A vertex is inserted
// only if it lies this close to the receiving polygon's plane: a neighbour's vertex a print step off the
// plane (EnergyPlus: 10 um) would tilt the polygon's triangles off its plane and break exact predicates on
// them (a wall no longer wholly facing away from the room behind it); float cracks are in-plane anyway.
// Points this close to each other on one edge are one point: inserting both would cut a triangle of no area.
inline constexpr double kSeamNoise = 1e-9;

// Coplanar neighbours give every boundary vertex near an edge: meshes whose unit normals, up to sign, fall in
// the same bins of this width on each axis (a rounding apart; two normals straddling a bin edge are not
// joined) and whose planes lie within kSeamNoise of each other. Across a crease (two planes meeting along a
// slanted line: DM1's 45-degree ceilings on its walls) only the ends of slanted edges that lie on the
// receiving edge's line within kSeamNoise are given, the corners both planes' intersections put there: a
// weld-distance match across planes (EnergyPlus walls standing on a floor's slanted edge, 10 um off it)
// would cut slivers whose float-rounded normals tilt by up to a few percent.
inline constexpr double kSeamNormalBin = 1e-6;

// Crease edges are matched by line: by direction in bins of kSeamNormalBin and by the line's point nearest
// the origin in bins of this (metres), far above the noise of corners on one line (1e-12 m; an edge 0.1 mm
// long moves that point by up to 1e-7 m at 100 m from the origin). Lines straddling a bin edge are not
// joined, and their crease keeps its crack.
inline constexpr double kCreaseLineBin = 1e-6;

// How far a dicing point on a slanted outline edge may lie off that edge (metres): the mesher places it from
// Clipper's integer coordinates (1 um units) and keeps it there, within one unit of the edge in the plane's
// frame; twice that for the corners' own rounding. Across a crease, consecutive boundary edges whose shared
// vertex lies this close to the line through their far ends are one outline edge: they are keyed, and a
// point is measured, by that edge's line (its corners), not by their own.
inline constexpr double kDicingPointNoise = 2e-6;

// Seams along an axis are left as they are: the two coordinates such an edge keeps are kept by every point on
// it, and float rounds them alike, so its T-junctions cannot open. Constant to this (metres), not bit for
// bit: corners the Quake reader's CSG meets in double differ by about 1e-15 m where they should agree (the
// mesher keeps such coordinates to the same noise), and an edge read as slanted in its coarse form but axial
// once diced took a neighbour's corner in one form only, so the coarse form could not be drawn from the
// diced vertices.
inline constexpr double kAxialNoise = 1e-9;

struct TJunctionStats {
  std::size_t vertices_inserted = 0;         // vertex copies added to edges
  std::size_t triangles_split = 0;           // triangles replaced by two or more
  std::size_t crease_vertices_inserted = 0;  // of vertices_inserted, across a crease between two planes
  std::size_t splits_refused = 0;            // triangles left whole: a piece would face away
};

// Inserts into each mesh's boundary edges (edges without a twin in their own mesh) the boundary vertices of
// the other coplanar meshes that lie within `tolerance` (metres) of the edge, farther than `tolerance` from
// both of its ends and within kSeamNoise of the mesh's plane; then, into slanted boundary edges, the ends of
// other meshes' slanted boundary edges on the line of the outline edge it was diced from (within kSeamNoise
// of it), as far from its ends, and the coplanar meshes of a mesh that took such a point are repaired again.
// An inserted vertex is an exact copy of the other mesh's vertex, so both sides round alike. A split triangle
// keeps its place in the list with the piece that holds the edge it shares with its quad partner (paired as
// the renderer pairs them to re-split quads), so pairs stay pairs; the other pieces go to the end.
// Orientation is kept. Meshes with no neighbours within tolerance are left exactly as they are.
TJunctionStats repair_t_junctions(std::vector<PolygonMesh>& meshes, double tolerance);

}  // namespace walk::compiler
