#pragma once
// On-disk layout of a .walk bundle: the one contract between the display compiler and the runtime.
// Little-endian, fixed-size POD records, every section 16-byte aligned and CRC-32 checked.
// Bump kBundleVersion whenever a record changes; readers refuse other versions.
#include <array>
#include <cstdint>

namespace walk::model {

inline constexpr std::array<char, 8> kBundleMagic{'W', 'A', 'L', 'K', 'B', 'N', 'D', 'L'};
// 4: CIRC says which light form each circuit is shown in; 5: LGHT, PLGT and LINT sparse
// (model/light_rows.hpp)
inline constexpr std::uint32_t kBundleVersion = 5;
inline constexpr std::uint64_t kSectionAlignment = 16;

// Tags of the sections, as four ASCII bytes read as a little-endian integer.
constexpr std::uint32_t tag(const char (&s)[5]) {
  return std::uint32_t(std::uint8_t(s[0])) | std::uint32_t(std::uint8_t(s[1])) << 8 |
         std::uint32_t(std::uint8_t(s[2])) << 16 | std::uint32_t(std::uint8_t(s[3])) << 24;
}

struct FileHeader {
  std::array<char, 8> magic;
  std::uint32_t version;
  std::uint32_t section_count;
  std::uint64_t file_size;
  std::uint32_t table_crc;  // CRC-32 of the section table that follows the header
  std::uint32_t reserved;
};
static_assert(sizeof(FileHeader) == 32);

struct SectionEntry {
  std::uint32_t tag;
  std::uint32_t record_size;
  std::uint64_t offset;
  std::uint64_t count;
  std::uint32_t crc;
  std::uint32_t reserved;
};
static_assert(sizeof(SectionEntry) == 32);

struct MetaRecord {
  double origin[3];  // world position of the local origin, metres
  float bounds_min[3];
  float bounds_max[3];
  float ambient;   // uniform ambient radiosity fraction added at display time (W/m2 per unit albedo)
  float exposure;  // radiosity (W/m2) that maps to display white
  std::uint64_t scene_hash;
  std::uint32_t circuit_count;
  std::uint32_t
      compiler_version;  // string offset: the `walk` that wrote it (0, the empty string: unrecorded)
};
static_assert(sizeof(MetaRecord) == 72);

struct VertexRecord {
  float position[3];  // local coordinates, metres
  float normal[3];
  float albedo[3];  // diffuse reflectance of the polygon
  std::uint32_t polygon;
};
static_assert(sizeof(VertexRecord) == 40);

struct PolygonRecord {
  std::uint32_t first_index;  // into INDX, a multiple of 3
  std::uint32_t index_count;
  std::uint32_t first_vertex;
  std::uint32_t vertex_count;
  std::uint32_t material;
  std::uint32_t group;
  std::uint32_t role;  // model::Role
  std::uint32_t name;  // string offset
};
static_assert(sizeof(PolygonRecord) == 32);

struct MaterialRecord {
  float reflectance[3];
  std::uint32_t name;
};
static_assert(sizeof(MaterialRecord) == 16);

struct GroupRecord {
  std::uint32_t name;
};

// How a circuit's light is shown: from the compact form (LCOL x LINT) where that is within the compiler's
// limit for this circuit, else from LGHT. LGHT always holds every circuit that reaches a vertex in full
// (probes and benches read it).
enum class LightForm : std::uint32_t { Full = 0, Compact = 1 };

struct CircuitRecord {
  std::uint32_t name;
  float default_level;
  float compact_scale = 0.0f;  // radiosity (W/m2) of compact intensity code 255, see LINT
  LightForm light_form = LightForm::Full;
  float compact_error =
      0.0f;  // this circuit's relative RMS error in the compact form (error RMS / light RMS)
};
static_assert(sizeof(CircuitRecord) == 20);

struct LuminaireRecord {
  float position[3];
  float normal[3];
  float u_axis[3];
  float width, height;
  float power[3];
  std::uint32_t circuit;
  std::uint32_t name;
};
static_assert(sizeof(LuminaireRecord) == 64);

// How a luminaire emits, optional (one per LUMS record; a bundle without LMSH has area panels only as far as
// readers know): kind is model::LuminaireKind; cone and exponent shape spots; distribution indexes DIST for
// photometric fixtures (aimed along `normal`, C0 towards `u_axis`), kNoDistribution otherwise.
inline constexpr std::uint32_t kNoDistribution = 0xffffffffu;
struct LuminaireShapeRecord {
  std::uint32_t kind;
  float cone;
  float exponent;
  std::uint32_t distribution;
};
static_assert(sizeof(LuminaireShapeRecord) == 16);

// A measured intensity table (model::IntensityDistribution): DSTV floats from `first`, gamma_count gamma
// angles, c_count C angles, then c_count x gamma_count candela, [c][gamma]; `lumens` its integrated flux.
struct DistributionRecord {
  std::uint32_t first;
  std::uint32_t gamma_count;
  std::uint32_t c_count;
  float lumens;
};
static_assert(sizeof(DistributionRecord) == 16);

// The coarse display while moving, optional: a polygon's fewest triangles (its outline, no lighting grid),
// as a range of CIDX whose indices are vertices of the polygon's own VERT range. One record per polygon.
struct CoarseRangeRecord {
  std::uint32_t first_index;  // into CIDX, a multiple of 3
  std::uint32_t index_count;
};
static_assert(sizeof(CoarseRangeRecord) == 8);

// A cell of the model-space subdivision with its potentially visible set (a range of PVSL).
// Cell flags. Outside: only the outside reaches it (inside_flood): off the walk, its PVS is empty and a
// renderer that finds the eye there draws everything.
inline constexpr std::uint32_t kCellOutside = 1;

struct CellRecord {
  float bounds_min[3];
  float bounds_max[3];
  std::uint32_t pvs_first;
  std::uint32_t pvs_count;
  std::uint32_t flags = 0;
  std::uint32_t reserved = 0;
};
static_assert(sizeof(CellRecord) == 40);

// The cells' portals, optional: where sight passes from one cell into another (the parts of a cell's boundary
// no opaque polygon covers). The renderer narrows its view through them each frame (Luebke & Georges 1995),
// so a frame draws what the eye's chains of portals show, not its cell's whole PVS. Each record is the box of
// one portal's outline, flat on its axis and rounded outward, joining `back` (on the -axis side) to `front`.
// Flags: the axis (0-2) in the low two bits, and which ways sight lines pass (one-way portals arise where
// back faces are culled; see compiler/partition/portals.hpp).
inline constexpr std::uint32_t kPortalAxisMask = 3;
inline constexpr std::uint32_t kPortalForward = 4;   // from `back` into `front`
inline constexpr std::uint32_t kPortalBackward = 8;  // from `front` into `back`
struct PortalRecord {
  float bounds_min[3];
  float bounds_max[3];
  std::uint32_t back;
  std::uint32_t front;
  std::uint32_t flags;
  std::uint32_t reserved = 0;
};
static_assert(sizeof(PortalRecord) == 40);

// A cluster: polygons of one object lying close together (or one shell polygon), the unit a PVS lists.
// Its polygons are a range of CLPO. A bundle without CLUS has one cluster per polygon, in polygon order.
struct ClusterRecord {
  float bounds_min[3];
  float bounds_max[3];
  std::uint32_t polygon_first;
  std::uint32_t polygon_count;
};
static_assert(sizeof(ClusterRecord) == 32);

// Levels of detail for moving frames, optional: each cluster simplified at compile time (meshoptimizer), its
// opaque triangles of the coarse form (CIDX) welded by position and reduced to about
// 1/2, 1/4 and 1/8. LODR holds kLodLevels records per cluster, finest first; a level with no indices means
// "as the level before". Indices are VERT ids, so the light of the original vertices mixes as ever.
inline constexpr std::uint32_t kLodLevels = 3;
struct LodRangeRecord {
  std::uint32_t first_index;  // into LODX, a multiple of 3
  std::uint32_t index_count;
  float error;  // metres: the furthest the simplified surface strays from the cluster's own
  std::uint32_t reserved = 0;
};
static_assert(sizeof(LodRangeRecord) == 16);

// Albedo maps, optional (a scene without textures has none of these sections and pays nothing). TEXR
// describes each texture, its texels a range of TEXL: 8-bit sRGB RGBA, rows bottom-up (GL's t = 0 first).
struct TextureRecord {
  std::uint32_t width;
  std::uint32_t height;
  std::uint64_t first_byte;  // into TEXL
  float mean[3];             // mean texel in linear light: the share of the polygon's reflectance it carries
  std::uint32_t name;        // as the model file names it
};
static_assert(sizeof(TextureRecord) == 32);

// One per polygon when TEXR is present: texture coordinates as affine functions of local position,
// u = dot(u[0..2], p) + u[3] (likewise v), and which texture (kNoTextureRecord: the polygon has none).
inline constexpr std::uint32_t kNoTextureRecord = UINT32_MAX;
struct PolygonTextureRecord {
  float u[4];
  float v[4];
  std::uint32_t texture;
  std::uint32_t reserved[3] = {0, 0, 0};
};
static_assert(sizeof(PolygonTextureRecord) == 48);

// A node of the cell tree: points with plane(p) >= 0 go to `front`. A negative child c is cell -c-1.
struct NodeRecord {
  double plane[4];
  std::int32_t front;
  std::int32_t back;
};
static_assert(sizeof(NodeRecord) == 40);

// What a compiler stage did: lets a later compile skip a stage whose inputs did not change.
struct StageRecord {
  std::uint32_t name;
  std::uint32_t ran;  // 1 when run, 0 when skipped (scene did not call for it)
  std::uint64_t input_hash;
  double seconds;
  std::uint64_t items_in;
  std::uint64_t items_out;
};
static_assert(sizeof(StageRecord) == 40);

namespace section {
inline constexpr std::uint32_t kMeta = tag("META");
inline constexpr std::uint32_t kVertices = tag("VERT");
inline constexpr std::uint32_t kIndices = tag("INDX");
inline constexpr std::uint32_t kPolygons = tag("POLY");
inline constexpr std::uint32_t kMaterials = tag("MATL");
inline constexpr std::uint32_t kGroups = tag("GRPS");
inline constexpr std::uint32_t kCircuits = tag("CIRC");
inline constexpr std::uint32_t kLuminaires = tag("LUMS");
inline constexpr std::uint32_t kLuminaireShapes = tag("LMSH");     // optional, see LuminaireShapeRecord
inline constexpr std::uint32_t kDistributions = tag("DIST");       // optional, see DistributionRecord
inline constexpr std::uint32_t kDistributionValues = tag("DSTV");  // float
// Light per vertex, sparse (model::LightRowsView): LGHT holds LightEntry records, the circuits that reach
// each vertex in increasing order; LGHR (u32, vertices + 1, or empty: no light anywhere) where each
// vertex's entries start.
inline constexpr std::uint32_t kLight = tag("LGHT");
inline constexpr std::uint32_t kLightRows = tag("LGHR");
// The paper's compact light form, optional: u8 RGBA average colour per vertex (LCOL), and per vertex the
// 8-bit intensity code of each circuit shown compact that reaches it (LINT: u32 circuit << 8 | code,
// model::CompactCodesView; LINR: u32, vertices + 1), coded logarithmically against
// CircuitRecord::compact_scale (model/compact_code.hpp). Radiosity = colour/255 x scale x the code's value.
inline constexpr std::uint32_t kCompactColour = tag("LCOL");
inline constexpr std::uint32_t kCompactIntensity = tag("LINT");
inline constexpr std::uint32_t kCompactIntensityRows = tag("LINR");
// Coarse display while moving, optional: per polygon and circuit the area mean of its patches, sparse as
// LGHT is (PLGR: u32, polygons + 1).
inline constexpr std::uint32_t kPolygonLight = tag("PLGT");
inline constexpr std::uint32_t kPolygonLightRows = tag("PLGR");
inline constexpr std::uint32_t kCoarseIndices = tag("CIDX");  // u32 vertex indices, see CoarseRangeRecord
inline constexpr std::uint32_t kCoarseRanges = tag("CRNG");
inline constexpr std::uint32_t kCells = tag("CELL");
inline constexpr std::uint32_t kNodes = tag("NODE");
inline constexpr std::uint32_t kPvs = tag("PVSL");       // cluster indices, per cell ranges
inline constexpr std::uint32_t kPortals = tag("PORT");   // optional, see PortalRecord
inline constexpr std::uint32_t kLeakPath = tag("LEAK");  // optional, float xyz: seed to the largest leak
// optional, u32 polygon indices (sorted): faces only the void round a sealed level sees
inline constexpr std::uint32_t kVoidFacing = tag("VOID");
inline constexpr std::uint32_t kClusters = tag("CLUS");         // optional, see ClusterRecord
inline constexpr std::uint32_t kClusterPolygons = tag("CLPO");  // u32 polygon indices of the clusters
inline constexpr std::uint32_t kLodIndices = tag("LODX");       // optional, u32 VERT ids, see LodRangeRecord
inline constexpr std::uint32_t kLodRanges = tag("LODR");        // optional, kLodLevels per cluster
inline constexpr std::uint32_t kTextures = tag("TEXR");         // optional, see TextureRecord
inline constexpr std::uint32_t kTexels = tag("TEXL");           // u8, see TextureRecord
inline constexpr std::uint32_t kPolygonTextures = tag("PTEX");  // one per polygon with TEXR
inline constexpr std::uint32_t kStages = tag("STAG");
inline constexpr std::uint32_t kStrings = tag("STRS");
}  // namespace section

}  // namespace walk::model
