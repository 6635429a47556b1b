#pragma once
// Measures a PVS against what can really be seen. For random viewpoints in every cell, six cube faces of
// polygon-ID images are ray cast over the full model (through glass); a pixel is missed when a polygon on its
// sight line is not in the cell's PVS: exactly the pixels where the PVS-only image would differ. Each cell's
// exact visible set is estimated as the union of IDs seen from a dense grid of viewpoints in it (a lower
// bound, so PVS/exact is an upper estimate of the overdraw ratio).
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "compiler/geometry/vis_geometry.hpp"
#include "compiler/partition/portals.hpp"
#include "compiler/raycast/ray_caster.hpp"
#include "model/bundle_format.hpp"

namespace walk::compiler {

struct VerifyOptions {
  int viewpoints = 4;          // random viewpoints per cell for the missed-pixel count
  int resolution = 512;        // cube face size for those
  int dense = 3;               // dense viewpoints per axis per cell (dense^3) for the exact set
  int dense_resolution = 128;  // cube face size for those
  std::string ray_caster = "axial";
  unsigned threads = 0;
  std::uint64_t seed = 7;
  // Viewpoints only where a walker can stand: in open space, not inside a solid or outside the model.
  bool free_space_only = true;
  // Judge the images the renderer draws: with back faces culled (its default), a polygon met from behind is
  // not drawn and what lies behind it shows.
  bool cull_back_faces = true;
  // Viewpoints beside each portal too (see portal_viewpoints), at dense_resolution, counted for missed
  // pixels and the exact set alike.
  bool portal_views = true;
  // Each pixel's sight line through a random point of the pixel rather than its centre. Pixel centres and
  // viewpoints a round millimetre off a cell face line up exactly with the corners of models drawn on round
  // coordinates (a 1/64 direction step from 1 mm off a wall meets a sill's edge at t = 0.064 exactly), so
  // the judge counted polygons touched only along an edge, which no area of the image shows.
  bool jitter = true;
};

// What the sight lines from a cell's viewpoints met: per pixel the ids along it (glass, then the stop).
struct CellViews {
  bool no_free_space = false;  // no free-space point found in the cell: viewpoints anywhere in it
  std::vector<std::uint32_t> ids;
  std::vector<std::uint32_t> offsets{0};  // pixel p's ids: ids[offsets[p] .. offsets[p+1])
  std::vector<std::uint32_t> exact;       // union over the dense viewpoints and these, sorted
  std::size_t portal_viewpoints = 0;      // of those kept, how many stood beside a portal
  // Each kept viewpoint and the first pixel its images start at, in order: which eye a missed pixel is from.
  std::vector<std::pair<model::Vec3, std::size_t>> eyes;
};

// Viewpoints beside the portals of `cell`: each portal's centre and up to kPortalCorners of its hull's
// corners pulled a tenth of the way to the centre, kept 1 mm inside the cell. A cell's widest views are from
// its portals, at the faces of its box, where the dense grid never stands: without them the exact set misses
// what a walker sees stepping up to a door, and the missed-pixel count never tests the PVS there.
inline constexpr int kPortalCorners = 4;

// A bundle's cells and their portals, recomputed from the stored cell boxes and polygons: portals are derived
// data, not stored. The partition's per-cell polygon lists are left empty.
struct BundleCells {
  Partition partition;
  PortalGraph graph;
};
[[nodiscard]] BundleCells bundle_cells(const std::vector<VisPolygon>& polygons,
                                       std::span<const model::CellRecord> cells, bool cull_back_faces);
[[nodiscard]] std::vector<model::Vec3> portal_viewpoints(const PortalGraph& graph, const Box& cell,
                                                         std::uint32_t cell_index);

class VisibilityJudge {
 public:
  // `void_facing` (the bundle's VOID): polygons only the void round a sealed level sees.
  VisibilityJudge(std::span<const model::VertexRecord> vertices, std::span<const std::uint32_t> indices,
                  std::span<const model::PolygonRecord> polygons, const VerifyOptions& options,
                  std::span<const std::uint32_t> void_facing = {});
  // `portal_eyes` (from portal_viewpoints) are looked from too, when options.portal_views is on.
  [[nodiscard]] CellViews views(const Box& cell, std::uint32_t cell_index,
                                std::span<const model::Vec3> portal_eyes = {}) const;
  // Whether `p` lies in open space: of 14 sight lines (axes and cube diagonals), more meet the front of a
  // polygon than its back. Inside a solid, in a thick wall or outside a closed model, the first polygons
  // met are seen from behind; in the void round a sealed level, they are void-facing and count as backs.
  // Glass and sight lines that leave the model count for neither.
  [[nodiscard]] bool in_free_space(const model::Vec3& p) const;
  // Pixels of `views` whose sight line meets a polygon not in `pvs` (sorted ids).
  [[nodiscard]] std::uint64_t missed(const CellViews& views, const std::vector<std::uint32_t>& pvs) const;
  [[nodiscard]] std::size_t polygon_count() const { return glass_.size(); }
  [[nodiscard]] const std::vector<VisPolygon>& polygons() const { return polygons_; }

 private:
  void cube(const model::Vec3& eye, int resolution, CellViews* keep, std::vector<char>& seen) const;
  VerifyOptions options_;
  std::vector<VisPolygon> polygons_;
  std::vector<char> glass_;
  std::vector<char> void_facing_;
  std::unique_ptr<RayCaster> caster_;
};

struct VerifyRow {
  std::uint32_t cell = 0;
  std::uint64_t pvs = 0, exact = 0, missed = 0, pixels = 0;
  // In clusters, the PVS's own unit: those in the PVS, and those with a polygon in the exact set (0 and 0
  // where the PVS is judged by polygons alone). A chair seen from a doorway is one cluster in both, while
  // its hundreds of polygons count in the PVS and the dozen a viewpoint sees in the exact set.
  std::uint64_t pvs_clusters = 0, exact_clusters = 0;
};

struct VerifyReport {
  std::size_t cells = 0, portals = 0, polygons = 0;
  std::uint64_t missed = 0, pixels = 0;
  double pvs_average = 0.0, exact_average = 0.0;
  std::uint64_t pvs_worst = 0;
  double ratio = 0.0;        // sum of PVS sizes / sum of exact sizes
  double ratio_worst = 0.0;  // worst cell's PVS / exact
  double reduction = 0.0;    // polygons / average PVS
  // The same in clusters, where the rows count them (else 0).
  double cluster_pvs_average = 0.0, cluster_exact_average = 0.0;
  double cluster_ratio = 0.0, cluster_ratio_worst = 0.0;
  std::vector<VerifyRow> rows;
};

// Per polygon, the index of the cluster holding it (a bundle's CLUS records over its CLPO list); polygons
// in no cluster get kNoCluster.
inline constexpr std::uint32_t kNoCluster = 0xffffffffu;
[[nodiscard]] std::vector<std::uint32_t> cluster_of_polygons(std::size_t polygons,
                                                             std::span<const model::ClusterRecord> clusters,
                                                             std::span<const std::uint32_t> cluster_polygons);
// How many distinct clusters hold the polygons `ids` (those in no cluster, or out of range, count none).
[[nodiscard]] std::uint64_t clusters_holding(std::span<const std::uint32_t> ids,
                                             std::span<const std::uint32_t> cluster_of);

// Summarises per-cell rows into a report (cells, portals and polygons filled by the caller).
void summarise(VerifyReport& report);

// Which cells to judge, given per cell whether its viewpoints found no open space. A cell with none, in a
// model where another found some, lies inside walls (a Quake level's cells cut through its brushes): no
// viewer stands there, and judging it from inside a wall counts pixels seen through its back faces, so it is
// not judged. A model with no open space anywhere (no closed rooms) is judged everywhere, from anywhere.
[[nodiscard]] std::vector<bool> cells_to_judge(const std::vector<bool>& no_open_space);

}  // namespace walk::compiler
