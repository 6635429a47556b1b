#pragma once
// Clusters as the renderer's unit of drawing. At load time each index form (fine INDX, coarse CIDX) is copied
// cluster by cluster into the renderer's own buffer, opaque polygons first and glass after, so a cluster is
// one range of each. Clusters keep the compiler's draw order (its Gray order of cell membership): clusters a
// cell sees together sit together and merge into one range. A frame's draw list is then made from the
// cell's PVS clusters and one box test each, with no per-polygon work (Complex buildings 2).
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "model/bundle.hpp"
#include "render/draw_list.hpp"
#include "render/frustum.hpp"
#include "render/portal_view.hpp"

namespace walk::render {

struct IndexRange {
  std::uint32_t first = 0;  // in indices
  std::uint32_t count = 0;
};

// What the layout is made from: a bundle's spans, or a test's own.
struct LayoutInput {
  std::span<const model::PolygonRecord> polygons;
  std::span<const model::VertexRecord> vertices;
  std::span<const std::uint32_t> indices;
  std::span<const model::CoarseRangeRecord> coarse_ranges;  // empty: no coarse form
  std::span<const std::uint32_t> coarse_indices;
  std::span<const model::ClusterRecord> clusters;  // empty: one cluster per polygon
  std::span<const std::uint32_t> cluster_polygons;
  std::span<const model::LodRangeRecord> lod_ranges;  // empty: no levels of detail
  std::span<const std::uint32_t> lod_indices;
};
[[nodiscard]] LayoutInput layout_input(const model::Bundle& bundle);

// One index form laid out by unit (a cluster in draw order).
struct LaidOutForm {
  std::vector<std::uint32_t> indices;
  std::vector<IndexRange> opaque, glass;  // per unit
  // Per polygon, its range in `indices` (count 0 when it is not drawn): what the diagonal choice rewrites.
  std::vector<model::PolygonRecord> polygons;
  // Levels of detail, in the coarse form (the one the compiler simplified; none without it): per unit,
  // kLodLevels opaque ranges laid out level by level after the glass, so units at one level still merge.
  // A level the bundle lacks repeats the one before (the unit's own range for the first); error in metres.
  std::vector<std::array<IndexRange, model::kLodLevels>> lod;
  std::vector<std::array<float, model::kLodLevels>> lod_error;
  // Where each region of `indices` starts: opaque, glass, then each level.
  std::vector<std::uint32_t> regions;
  // The coarse form's own vertices: the VERT record each copies, numbered by first use within each unit's
  // range. A software vertex stage (llvmpipe's draw module) fetches and shades a draw's index span [min,
  // max] in one run when that is no longer than the draw: over VERT's numbering a simplified cluster's few
  // triangles span every diced vertex of its polygons. The polygons of a unit share a vertex where their
  // corners coincide (bit for bit), and each triangle ends on a vertex of its own polygon (its provoking
  // vertex, which carries the flat polygon light): vertices of each polygon's own cost Sibenik, whose
  // polygons are mostly one triangle, three a triangle. Empty for the fine form, whose light is fetched by
  // gl_VertexID and so keeps VERT's numbering.
  std::vector<std::uint32_t> vertices;
  [[nodiscard]] bool empty() const { return indices.empty() && opaque.empty(); }
};

// How coarse a frame may draw: a unit is drawn at its coarsest level whose error, seen from `eye` at the
// unit box's nearest point, spans at most `max_pixels` pixels.
struct LodChoice {
  glm::vec3 eye{0.0f};
  float pixels_per_radian = 1.0f;  // image height / vertical field of view (radians), near the centre
  float max_pixels = 0.0f;         // 0: full detail
  bool leave_out_small = true;     // too_small_to_draw units are left out
};

struct ClusterLayout {
  std::vector<Box> boxes;              // per unit: the box of its drawn polygons (empty box: nothing drawn)
  std::vector<std::uint32_t> drawn;    // per unit: polygons drawn
  std::vector<std::uint32_t> unit_of;  // per PVS id (a bundle cluster, or a polygon without CLUS)
  // Per polygon, the unit that draws it (kNoUnit: none, e.g. an opening).
  static constexpr std::uint32_t kNoUnit = UINT32_MAX;
  std::vector<std::uint32_t> unit_of_polygon;
  LaidOutForm fine, coarse;  // coarse is empty when the bundle has no coarse form
  [[nodiscard]] std::size_t units() const { return boxes.size(); }
};

// How the coarse form's vertices are made (LaidOutForm::vertices): shared between the polygons of a unit
// where their corners coincide (the renderer's), or each polygon's own, as VERT has them (its A/B).
enum class CoarseVertices { Shared, OwnPerPolygon };

[[nodiscard]] ClusterLayout lay_out_clusters(const LayoutInput& input,
                                             CoarseVertices coarse_vertices = CoarseVertices::Shared);

// The units of `pvs_ids` (bundle cluster ids, or polygon ids without CLUS), sorted, duplicates and
// out-of-range ids dropped.
[[nodiscard]] std::vector<std::uint32_t> units_of(const ClusterLayout& layout,
                                                  std::span<const std::uint32_t> pvs_ids);
// Every unit, in order.
[[nodiscard]] std::vector<std::uint32_t> all_units(const ClusterLayout& layout);

// The draw list of `units` (sorted) in `form`, less the units whose box lies outside `frustum` and those
// `portals` does not show, when given; ranges that meet are merged.
// With `lod`, units too small to draw are left out and (in a form that has levels) each unit's opaque
// range is its level's. With `nearest_first` (the eye), the opaque ranges go in order of their distance
// from it, ties by unit, so an early depth test can reject what nearer units hide: units adjacent in the
// buffer form runs of up to `run_triangles`, each run placed by its nearest unit's box distance (0: every
// unit on its own); ranges then merge only where that order keeps them adjacent. Glass keeps the units'
// order.
[[nodiscard]] DrawList cluster_draw_list(const ClusterLayout& layout, const LaidOutForm& form,
                                         std::span<const std::uint32_t> units, const Frustum* frustum,
                                         const LodChoice* lod = nullptr, const PortalView* portals = nullptr,
                                         const glm::vec3* nearest_first = nullptr,
                                         std::uint32_t run_triangles = kNearestFirstRunTriangles);
// The triangles `units` draw in `form`, each at the level `lod` picks (its own range without), less those
// too small to draw.
[[nodiscard]] std::uint32_t triangles_of(const ClusterLayout& layout, const LaidOutForm& form,
                                         std::span<const std::uint32_t> units, const LodChoice* lod);
// Whether unit `u` is left out of a frame with a pixel budget: its whole box (the diagonal) spans at most
// `max_pixels` seen from the box's nearest point, so leaving it out moves what the frame shows by no more
// than a level of detail within the budget would (Funkhouser & Sequin's detail elision). Never at full
// detail (max_pixels 0), nor with the eye in its box. Such a cluster spans under a cell of the occlusion
// buffer (about 11 pixels at 1280 wide), so as an occluder it never covered one whole and hid nothing.
[[nodiscard]] bool too_small_to_draw(const ClusterLayout& layout, std::uint32_t u, const LodChoice& lod);
// The level `lod` picks for unit `u` of `form` (0: its own range; l + 1: LOD level l).
[[nodiscard]] int lod_level(const ClusterLayout& layout, const LaidOutForm& form, std::uint32_t u,
                            const LodChoice& lod);

}  // namespace walk::render
