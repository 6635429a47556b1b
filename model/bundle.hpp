#pragma once
// Writing and reading .walk bundles. The writer builds the file in a temporary name and renames it, so a
// failed compile never leaves a partial bundle. The reader maps the file and validates every offset, count,
// cross-reference and checksum before handing out views, so the runtime can trust what it reads.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/bundle_format.hpp"
#include "model/light_rows.hpp"

namespace walk::model {

// Everything a bundle holds, as owned vectors: what the compiler fills in and the writer serialises.
struct BundleContents {
  MetaRecord meta{};
  std::vector<VertexRecord> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<PolygonRecord> polygons;
  std::vector<MaterialRecord> materials;
  std::vector<GroupRecord> groups;
  std::vector<CircuitRecord> circuits;
  std::vector<LuminaireRecord> luminaires;
  std::vector<LuminaireShapeRecord> luminaire_shapes;  // empty, or one per luminaire
  std::vector<DistributionRecord> distributions;
  std::vector<float> distribution_values;
  LightRows light;                                          // one row per vertex, or none: no light
  std::vector<std::array<std::uint8_t, 4>> compact_colour;  // empty, or one per vertex
  CompactCodes compact_intensity;                           // empty, or one row per vertex
  LightRows polygon_light;                                  // empty, or one row per polygon
  std::vector<std::uint32_t> coarse_indices;                // empty, or CIDX
  std::vector<CoarseRangeRecord> coarse_ranges;             // empty, or one per polygon
  std::vector<CellRecord> cells;
  std::vector<NodeRecord> nodes;
  std::vector<PortalRecord> portals;  // empty, or the cells' portals
  std::vector<std::uint32_t> pvs;     // cluster ids (polygon ids when `clusters` is empty)
  std::vector<ClusterRecord> clusters;
  std::vector<std::uint32_t> cluster_polygons;
  std::vector<std::uint32_t> lod_indices;       // empty, or LODX
  std::vector<LodRangeRecord> lod_ranges;       // empty, or kLodLevels per cluster
  std::vector<std::array<float, 3>> leak_path;  // empty, or seed -> portals -> the largest leak (local)
  // Polygons (sorted) whose front only the void round a sealed level sees (qbsp's outside faces): with
  // solids, the open regions an outside flood reaches and the inside one does not.
  std::vector<std::uint32_t> void_facing;
  std::vector<TextureRecord> textures;                 // empty, or the albedo maps
  std::vector<std::uint8_t> texels;                    // TEXL
  std::vector<PolygonTextureRecord> polygon_textures;  // empty, or one per polygon
  std::vector<StageRecord> stages;
  std::string strings{'\0'};  // offset 0 is the empty string

  // Appends a NUL-terminated string and returns its offset.
  std::uint32_t add_string(std::string_view s);
};

// The polygons of the clusters in `cell`'s PVS, sorted. Without clusters, PVSL lists polygons.
[[nodiscard]] std::vector<std::uint32_t> cell_polygons(const CellRecord& cell,
                                                       std::span<const std::uint32_t> pvs,
                                                       std::span<const ClusterRecord> clusters,
                                                       std::span<const std::uint32_t> cluster_polygons);

// Writes atomically: temp file in the same folder, fsync, rename. Throws walk::Error on failure.
void write_bundle(const std::string& path, const BundleContents& contents);

class Bundle {
 public:
  // Maps and validates `path`; throws walk::Error naming the file and the first problem found.
  static std::unique_ptr<Bundle> open(const std::string& path);
  ~Bundle();
  Bundle(const Bundle&) = delete;
  Bundle& operator=(const Bundle&) = delete;

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const MetaRecord& meta() const { return *meta_; }
  [[nodiscard]] std::span<const VertexRecord> vertices() const { return vertices_; }
  [[nodiscard]] std::span<const std::uint32_t> indices() const { return indices_; }
  [[nodiscard]] std::span<const PolygonRecord> polygons() const { return polygons_; }
  [[nodiscard]] std::span<const MaterialRecord> materials() const { return materials_; }
  [[nodiscard]] std::span<const GroupRecord> groups() const { return groups_; }
  [[nodiscard]] std::span<const CircuitRecord> circuits() const { return circuits_; }
  [[nodiscard]] std::span<const LuminaireRecord> luminaires() const { return luminaires_; }
  // Empty in bundles written before shapes were stored: then every luminaire reads as an area panel.
  [[nodiscard]] std::span<const LuminaireShapeRecord> luminaire_shapes() const { return luminaire_shapes_; }
  [[nodiscard]] std::span<const DistributionRecord> distributions() const { return distributions_; }
  [[nodiscard]] std::span<const float> distribution_values() const { return distribution_values_; }
  // Per vertex; empty where no light reaches any vertex (no luminaires).
  [[nodiscard]] LightRowsView light() const { return light_; }
  [[nodiscard]] std::span<const std::array<std::uint8_t, 4>> compact_colour() const {
    return compact_colour_;
  }
  [[nodiscard]] CompactCodesView compact_intensity() const { return compact_intensity_; }
  [[nodiscard]] LightRowsView polygon_light() const { return polygon_light_; }
  // Empty when the bundle has no coarse form (draw INDX instead).
  [[nodiscard]] std::span<const std::uint32_t> coarse_indices() const { return coarse_indices_; }
  [[nodiscard]] std::span<const CoarseRangeRecord> coarse_ranges() const { return coarse_ranges_; }
  [[nodiscard]] std::span<const CellRecord> cells() const { return cells_; }
  [[nodiscard]] std::span<const NodeRecord> nodes() const { return nodes_; }
  // Empty when the compiler found none (one cell) or wrote a bundle before portals were stored.
  [[nodiscard]] std::span<const PortalRecord> portals() const { return portals_; }
  [[nodiscard]] std::span<const std::uint32_t> pvs() const { return pvs_; }  // cluster ids
  [[nodiscard]] std::span<const ClusterRecord> clusters() const { return clusters_; }
  [[nodiscard]] std::span<const std::array<float, 3>> leak_path() const { return leak_path_; }
  [[nodiscard]] std::span<const std::uint32_t> void_facing() const { return void_facing_; }
  [[nodiscard]] std::span<const std::uint32_t> cluster_polygons() const { return cluster_polygons_; }
  // Empty, or kLodLevels records per cluster over lod_indices().
  [[nodiscard]] std::span<const std::uint32_t> lod_indices() const { return lod_indices_; }
  [[nodiscard]] std::span<const LodRangeRecord> lod_ranges() const { return lod_ranges_; }
  // Empty when the scene has no albedo maps; otherwise every polygon has a PolygonTextureRecord.
  [[nodiscard]] std::span<const TextureRecord> textures() const { return textures_; }
  [[nodiscard]] std::span<const std::uint8_t> texels() const { return texels_; }
  [[nodiscard]] std::span<const PolygonTextureRecord> polygon_textures() const { return polygon_textures_; }
  // The polygons `cell` may see (its PVS's clusters expanded), sorted.
  [[nodiscard]] std::vector<std::uint32_t> cell_polygons(std::uint32_t cell) const;
  [[nodiscard]] std::span<const StageRecord> stages() const { return stages_; }
  [[nodiscard]] std::string_view string(std::uint32_t offset) const;  // validated at open
  [[nodiscard]] std::uint64_t file_size() const { return size_; }

  // Cell containing a local-coordinate point, by walking the node tree: O(tree depth).
  [[nodiscard]] std::uint32_t locate_cell(const double p[3]) const;

 private:
  Bundle() = default;
  void validate();
  void validate_textures() const;
  void validate_luminaire_shapes() const;
  bool validate_row_starts(std::span<const std::uint32_t> first, std::size_t entries, std::size_t expected,
                           const std::string& name) const;
  void validate_light_rows(const LightRowsView& rows, std::size_t expected, const char* what) const;
  void validate_compact_codes() const;

  std::string path_;
  void* map_ = nullptr;
  std::uint64_t size_ = 0;
  const MetaRecord* meta_ = nullptr;
  std::span<const VertexRecord> vertices_;
  std::span<const std::uint32_t> indices_;
  std::span<const PolygonRecord> polygons_;
  std::span<const MaterialRecord> materials_;
  std::span<const GroupRecord> groups_;
  std::span<const CircuitRecord> circuits_;
  std::span<const LuminaireRecord> luminaires_;
  std::span<const LuminaireShapeRecord> luminaire_shapes_;
  std::span<const DistributionRecord> distributions_;
  std::span<const float> distribution_values_;
  LightRowsView light_;
  std::span<const std::array<std::uint8_t, 4>> compact_colour_;
  CompactCodesView compact_intensity_;
  LightRowsView polygon_light_;
  std::span<const std::uint32_t> coarse_indices_;
  std::span<const CoarseRangeRecord> coarse_ranges_;
  std::span<const CellRecord> cells_;
  std::span<const NodeRecord> nodes_;
  std::span<const PortalRecord> portals_;
  std::span<const std::uint32_t> pvs_;
  std::span<const ClusterRecord> clusters_;
  std::span<const std::array<float, 3>> leak_path_;
  std::span<const std::uint32_t> void_facing_;
  std::span<const std::uint32_t> cluster_polygons_;
  std::span<const std::uint32_t> lod_indices_;
  std::span<const LodRangeRecord> lod_ranges_;
  std::span<const TextureRecord> textures_;
  std::span<const std::uint8_t> texels_;
  std::span<const PolygonTextureRecord> polygon_textures_;
  std::span<const StageRecord> stages_;
  std::span<const char> strings_;
};

}  // namespace walk::model
