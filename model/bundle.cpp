#include "model/bundle.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>

#include "model/error.hpp"

namespace walk::model {
namespace {

std::uint32_t crc_of(const void* data, std::uint64_t size) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto* bytes = static_cast<const Bytef*>(data);
  while (size > 0) {  // zlib takes uInt lengths
    const uInt chunk = static_cast<uInt>(std::min<std::uint64_t>(size, 1u << 30));
    crc = crc32(crc, bytes, chunk);
    bytes += chunk;
    size -= chunk;
  }
  return static_cast<std::uint32_t>(crc);
}

std::string tag_name(std::uint32_t t) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((t >> (8 * i)) & 0xff);
    s[i] = (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

std::uint64_t align_up(std::uint64_t v) {
  return (v + kSectionAlignment - 1) / kSectionAlignment * kSectionAlignment;
}

struct PendingSection {
  std::uint32_t tag;
  std::uint32_t record_size;
  const void* data;
  std::uint64_t count;
};

template <typename T>
PendingSection pending(std::uint32_t tag, const std::vector<T>& v) {
  return {tag, sizeof(T), v.data(), v.size()};
}

// Closes the descriptor and removes the temporary file unless released: no partial bundle is ever left.
class TempFile {
 public:
  explicit TempFile(std::string path) : path_(std::move(path)) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!released_) ::unlink(path_.c_str());
  }
  [[nodiscard]] int fd() const { return fd_; }
  void release() { released_ = true; }

 private:
  std::string path_;
  int fd_ = -1;
  bool released_ = false;
};

void write_all(int fd, const void* data, std::uint64_t size, const std::string& path) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(located(path, 0, std::string("cannot write bundle: ") + std::strerror(errno),
                          "check free disk space and folder permissions"));
    }
    p += n;
    size -= static_cast<std::uint64_t>(n);
  }
}

}  // namespace

std::uint32_t BundleContents::add_string(std::string_view s) {
  if (s.empty()) return 0;
  const auto offset = static_cast<std::uint32_t>(strings.size());
  strings.append(s);
  strings.push_back('\0');
  return offset;
}

// Sparse rows' starts (LGHR, PLGR, LINR over `entries` records of `name`): none (and no entries), or
// `expected` rows whose starts climb from 0 to the entry count. False where there are no rows.
bool Bundle::validate_row_starts(std::span<const std::uint32_t> first, std::size_t entries,
                                 std::size_t expected, const std::string& name) const {
  const auto fail = [&](const std::string& problem) {
    throw Error(
        located(path_, 0, "corrupt bundle: " + name + " " + problem, "recompile it with `walk compile`"));
  };
  if (first.empty()) {
    if (entries != 0) fail("has entries but no row starts");
    return false;
  }
  if (first.size() - 1 != expected)
    fail("has " + std::to_string(first.size() - 1) + " rows, expected " + std::to_string(expected));
  if (first.front() != 0 || first.back() != entries)
    fail("row starts do not span its " + std::to_string(entries) + " entries");
  for (std::size_t r = 0; r + 1 < first.size(); ++r)
    if (first[r + 1] < first[r]) fail("row " + std::to_string(r) + " ends before it starts");
  return true;
}

// `what`'s rows: none, or `expected` rows, each listing valid circuits in increasing order with finite,
// non-negative radiosity.
void Bundle::validate_light_rows(const LightRowsView& rows, std::size_t expected, const char* what) const {
  const std::string name(what);
  if (!validate_row_starts(rows.first, rows.entries.size(), expected, name)) return;
  const auto fail = [&](const std::string& problem) {
    throw Error(
        located(path_, 0, "corrupt bundle: " + name + " " + problem, "recompile it with `walk compile`"));
  };
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    std::uint32_t next = 0;
    for (const LightEntry& e : rows.row(r)) {
      if (e.circuit < next || e.circuit >= circuits_.size())
        fail("row " + std::to_string(r) + " names circuit " + std::to_string(e.circuit) +
             " out of order or out of range");
      next = e.circuit + 1;
      for (const float v : e.rgb)
        if (!std::isfinite(v) || v < 0.0f) fail("holds a negative or non-finite radiosity");
    }
  }
}

// LINT's rows: none, or one per vertex, each naming circuits shown compact in increasing order with a
// non-zero code.
void Bundle::validate_compact_codes() const {
  const CompactCodesView& rows = compact_intensity_;
  if (!validate_row_starts(rows.first, rows.codes.size(), vertices_.size(), "LINT")) return;
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    std::uint32_t next = 0;
    for (const std::uint32_t e : rows.row(r)) {
      const std::uint32_t c = code_circuit(e);
      if (c < next || c >= circuits_.size() || code_value(e) == 0 ||
          circuits_[c].light_form != LightForm::Compact)
        throw Error(located(path_, 0,
                            "corrupt bundle: LINT row " + std::to_string(r) + " holds a code of circuit " +
                                std::to_string(c) +
                                " out of order, out of range, zero, or of a circuit not shown compact",
                            "recompile it with `walk compile`"));
      next = c + 1;
    }
  }
}

void Bundle::validate_luminaire_shapes() const {
  const auto fail = [&](const std::string& what) {
    throw Error(located(path_, 0, "corrupt bundle: " + what, "recompile it with `walk compile`"));
  };
  if (!luminaire_shapes_.empty() && luminaire_shapes_.size() != luminaires_.size())
    fail("LMSH holds " + std::to_string(luminaire_shapes_.size()) + " records, expected one per luminaire");
  for (std::size_t i = 0; i < luminaire_shapes_.size(); ++i) {
    const auto& l = luminaire_shapes_[i];
    const std::string name = "LMSH " + std::to_string(i);
    if (l.kind > 3) fail(name + " has an unknown kind");
    if (!std::isfinite(l.cone) || !std::isfinite(l.exponent) || l.exponent < 0.0f)
      fail(name + " has a non-finite cone or a negative exponent");
    if ((l.kind == 3) != (l.distribution != kNoDistribution) ||
        (l.distribution != kNoDistribution && l.distribution >= distributions_.size()))
      fail(name + " refers to a distribution out of range, or a fixture lacks one");
  }
  for (std::size_t i = 0; i < distributions_.size(); ++i) {
    const auto& d = distributions_[i];
    const std::uint64_t values =
        std::uint64_t(d.gamma_count) + d.c_count + std::uint64_t(d.gamma_count) * d.c_count;
    if (d.gamma_count == 0 || d.c_count == 0 || d.first > distribution_values_.size() ||
        values > distribution_values_.size() - d.first || !(d.lumens > 0.0f))
      fail("DIST " + std::to_string(i) + " runs past DSTV, is empty or emits nothing");
  }
  for (float v : distribution_values_)
    if (!std::isfinite(v) || v < 0.0f) fail("DSTV holds a negative or non-finite value");
}

void Bundle::validate_textures() const {
  const auto fail = [&](const std::string& what) {
    throw Error(located(path_, 0, "corrupt bundle: " + what, "recompile it with `walk compile`"));
  };
  if (textures_.empty() != polygon_textures_.empty()) fail("TEXR and PTEX come together");
  if (textures_.empty()) {
    if (!texels_.empty()) fail("TEXL without TEXR");
    return;
  }
  if (polygon_textures_.size() != polygons_.size())
    fail("PTEX holds " + std::to_string(polygon_textures_.size()) + " records, expected one per polygon (" +
         std::to_string(polygons_.size()) + ")");
  for (std::size_t i = 0; i < textures_.size(); ++i) {
    const auto& t = textures_[i];
    const std::uint64_t bytes = std::uint64_t(t.width) * t.height * 4;
    if (t.width == 0 || t.height == 0 || t.first_byte > texels_.size() ||
        bytes > texels_.size() - t.first_byte)
      fail("TEXR " + std::to_string(i) + " is empty or its texels run past TEXL");
    for (float m : t.mean)
      if (!std::isfinite(m) || m <= 0.0f || m > 1.0f) fail("TEXR " + std::to_string(i) + " has a bad mean");
    if (t.name >= strings_.size()) fail("TEXR " + std::to_string(i) + " name offset out of range");
  }
  for (std::size_t i = 0; i < polygon_textures_.size(); ++i) {
    const auto& p = polygon_textures_[i];
    if (p.texture != kNoTextureRecord && p.texture >= textures_.size())
      fail("PTEX " + std::to_string(i) + " refers to a texture out of range");
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(p.u[k]) || !std::isfinite(p.v[k]))
        fail("PTEX " + std::to_string(i) + " has a non-finite coordinate");
  }
}

void write_bundle(const std::string& path, const BundleContents& c) {
  const std::vector<MetaRecord> meta{c.meta};
  const std::vector<PendingSection> sections{
      pending(section::kMeta, meta),
      pending(section::kVertices, c.vertices),
      pending(section::kIndices, c.indices),
      pending(section::kPolygons, c.polygons),
      pending(section::kMaterials, c.materials),
      pending(section::kGroups, c.groups),
      pending(section::kCircuits, c.circuits),
      pending(section::kLuminaires, c.luminaires),
      pending(section::kLuminaireShapes, c.luminaire_shapes),
      pending(section::kDistributions, c.distributions),
      pending(section::kDistributionValues, c.distribution_values),
      pending(section::kLight, c.light.entries),
      pending(section::kLightRows, c.light.first),
      pending(section::kCompactColour, c.compact_colour),
      pending(section::kCompactIntensity, c.compact_intensity.codes),
      pending(section::kCompactIntensityRows, c.compact_intensity.first),
      pending(section::kPolygonLight, c.polygon_light.entries),
      pending(section::kPolygonLightRows, c.polygon_light.first),
      pending(section::kCoarseIndices, c.coarse_indices),
      pending(section::kCoarseRanges, c.coarse_ranges),
      pending(section::kCells, c.cells),
      pending(section::kNodes, c.nodes),
      pending(section::kPortals, c.portals),
      pending(section::kPvs, c.pvs),
      pending(section::kClusters, c.clusters),
      pending(section::kLeakPath, c.leak_path),
      pending(section::kVoidFacing, c.void_facing),
      pending(section::kClusterPolygons, c.cluster_polygons),
      pending(section::kLodIndices, c.lod_indices),
      pending(section::kLodRanges, c.lod_ranges),
      pending(section::kTextures, c.textures),
      pending(section::kTexels, c.texels),
      pending(section::kPolygonTextures, c.polygon_textures),
      pending(section::kStages, c.stages),
      PendingSection{section::kStrings, 1, c.strings.data(), c.strings.size()}};

  std::vector<SectionEntry> table(sections.size());
  std::uint64_t offset = align_up(sizeof(FileHeader) + sizeof(SectionEntry) * sections.size());
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const auto& s = sections[i];
    const std::uint64_t bytes = s.record_size * s.count;
    table[i] = SectionEntry{s.tag, s.record_size, offset, s.count, crc_of(s.data, bytes), 0};
    offset = align_up(offset + bytes);
  }
  FileHeader header{kBundleMagic,
                    kBundleVersion,
                    static_cast<std::uint32_t>(sections.size()),
                    offset,
                    crc_of(table.data(), table.size() * sizeof(SectionEntry)),
                    0};

  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  TempFile file(temp);
  if (file.fd() < 0)
    throw Error(located(path, 0, std::string("cannot create bundle: ") + std::strerror(errno),
                        "check that the output folder exists and is writable"));
  static const char zeros[kSectionAlignment] = {};
  std::uint64_t written = 0;
  auto put = [&](const void* data, std::uint64_t size) {
    write_all(file.fd(), data, size, path);
    written += size;
  };
  auto pad_to = [&](std::uint64_t target) { put(zeros, target - written); };
  put(&header, sizeof header);
  put(table.data(), table.size() * sizeof(SectionEntry));
  for (std::size_t i = 0; i < sections.size(); ++i) {
    pad_to(table[i].offset);
    put(sections[i].data, sections[i].record_size * sections[i].count);
  }
  pad_to(header.file_size);
  if (::fsync(file.fd()) != 0 || ::rename(temp.c_str(), path.c_str()) != 0)
    throw Error(located(path, 0, std::string("cannot finish bundle: ") + std::strerror(errno)));
  file.release();
}

std::unique_ptr<Bundle> Bundle::open(const std::string& path) {
  std::unique_ptr<Bundle> b(new Bundle());
  b->path_ = path;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw Error(located(path, 0, std::string("cannot open bundle: ") + std::strerror(errno),
                        "run `walk compile scene.toml -o " + path + "` first"));
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw Error(located(path, 0, "is a folder, not a bundle", "name the .walk file inside it"));
  }
  if (::fstat(fd, &st) != 0 || st.st_size < static_cast<off_t>(sizeof(FileHeader))) {
    ::close(fd);
    throw Error(located(path, 0, "not a bundle: file is too short", "recompile it with `walk compile`"));
  }
  b->size_ = static_cast<std::uint64_t>(st.st_size);
  b->map_ = ::mmap(nullptr, b->size_, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (b->map_ == MAP_FAILED) {
    b->map_ = nullptr;
    throw Error(located(path, 0, std::string("cannot map bundle: ") + std::strerror(errno)));
  }
  b->validate();
  return b;
}

Bundle::~Bundle() {
  if (map_) ::munmap(map_, size_);
}

std::string_view Bundle::string(std::uint32_t offset) const {
  if (offset >= strings_.size()) return {};
  return std::string_view(strings_.data() + offset);
}

void Bundle::validate() {
  const auto* base = static_cast<const char*>(map_);
  auto fail = [&](const std::string& what) {
    throw Error(located(path_, 0, "corrupt bundle: " + what, "recompile it with `walk compile`"));
  };
  FileHeader header;
  std::memcpy(&header, base, sizeof header);
  if (header.magic != kBundleMagic) fail("bad magic (not a .walk bundle)");
  if (header.version != kBundleVersion)
    throw Error(located(path_, 0,
                        "bundle format version " + std::to_string(header.version) +
                            ", this build reads version " + std::to_string(kBundleVersion),
                        "recompile it from its scene with this build's `walk compile`"));
  if (header.file_size != size_)
    fail("header says " + std::to_string(header.file_size) + " bytes, file has " + std::to_string(size_));
  if (header.section_count > 64) fail("implausible section count " + std::to_string(header.section_count));
  const std::uint64_t table_bytes = std::uint64_t(header.section_count) * sizeof(SectionEntry);
  if (sizeof(FileHeader) + table_bytes > size_) fail("section table runs past the end of the file");
  const auto* table = reinterpret_cast<const SectionEntry*>(base + sizeof(FileHeader));
  if (crc_of(table, table_bytes) != header.table_crc) fail("section table checksum mismatch");

  std::map<std::uint32_t, const SectionEntry*> by_tag;
  for (std::uint32_t i = 0; i < header.section_count; ++i) {
    const SectionEntry& e = table[i];
    const std::string name = "section " + tag_name(e.tag);
    if (e.record_size == 0) fail(name + " has zero record size");
    if (e.offset % kSectionAlignment != 0) fail(name + " is misaligned");
    if (e.count > size_ / e.record_size) fail(name + " count " + std::to_string(e.count) + " is too large");
    const std::uint64_t bytes = e.count * e.record_size;
    if (e.offset > size_ || bytes > size_ - e.offset) fail(name + " runs past the end of the file");
    if (crc_of(base + e.offset, bytes) != e.crc) fail(name + " checksum mismatch");
    if (!by_tag.emplace(e.tag, &e).second) fail(name + " appears twice");
  }
  auto get = [&]<typename T>(std::uint32_t t, std::span<const T>& out, bool required) {
    auto it = by_tag.find(t);
    if (it == by_tag.end()) {
      if (required) fail("section " + tag_name(t) + " is missing");
      return;
    }
    if (it->second->record_size != sizeof(T))
      fail("section " + tag_name(t) + " has record size " + std::to_string(it->second->record_size) +
           ", expected " + std::to_string(sizeof(T)));
    out = std::span<const T>(reinterpret_cast<const T*>(base + it->second->offset), it->second->count);
  };
  std::span<const MetaRecord> meta;
  get(section::kMeta, meta, true);
  if (meta.size() != 1) fail("META must hold exactly one record");
  meta_ = &meta[0];
  get(section::kVertices, vertices_, true);
  get(section::kIndices, indices_, true);
  get(section::kPolygons, polygons_, true);
  get(section::kMaterials, materials_, true);
  get(section::kGroups, groups_, true);
  get(section::kCircuits, circuits_, true);
  get(section::kLuminaires, luminaires_, true);
  get(section::kLuminaireShapes, luminaire_shapes_, false);
  get(section::kDistributions, distributions_, false);
  get(section::kDistributionValues, distribution_values_, false);
  get(section::kLight, light_.entries, true);
  get(section::kLightRows, light_.first, true);
  get(section::kCompactColour, compact_colour_, false);
  get(section::kCompactIntensity, compact_intensity_.codes, false);
  get(section::kCompactIntensityRows, compact_intensity_.first, false);
  get(section::kPolygonLight, polygon_light_.entries, false);
  get(section::kPolygonLightRows, polygon_light_.first, false);
  get(section::kCoarseIndices, coarse_indices_, false);
  get(section::kCoarseRanges, coarse_ranges_, false);
  get(section::kCells, cells_, true);
  get(section::kNodes, nodes_, true);
  get(section::kPortals, portals_, false);
  get(section::kPvs, pvs_, true);
  get(section::kClusters, clusters_, false);
  get(section::kLeakPath, leak_path_, false);
  get(section::kVoidFacing, void_facing_, false);
  get(section::kClusterPolygons, cluster_polygons_, false);
  get(section::kLodIndices, lod_indices_, false);
  get(section::kLodRanges, lod_ranges_, false);
  get(section::kTextures, textures_, false);
  get(section::kTexels, texels_, false);
  get(section::kPolygonTextures, polygon_textures_, false);
  get(section::kStages, stages_, true);
  get(section::kStrings, strings_, true);

  // Cross-references: after this, no index in the bundle can point outside its target.
  if (strings_.empty() || strings_.back() != '\0') fail("string table is not NUL-terminated");
  auto check_string = [&](std::uint32_t offset, const char* what) {
    if (offset >= strings_.size()) fail(std::string(what) + " name offset out of range");
  };
  if (meta_->circuit_count != circuits_.size()) fail("META circuit count disagrees with CIRC");
  check_string(meta_->compiler_version, "META compiler version");
  if (!std::isfinite(meta_->exposure) || meta_->exposure <= 0.0f) fail("META exposure must be positive");
  validate_light_rows(light_, vertices_.size(), "LGHT");
  if (!compact_colour_.empty() && compact_colour_.size() != vertices_.size())
    fail("LCOL must hold one colour per vertex");
  if (compact_colour_.empty() != compact_intensity_.empty()) fail("LCOL and LINT come together");
  validate_light_rows(polygon_light_, polygons_.size(), "PLGT");
  for (std::size_t i = 0; i < circuits_.size(); ++i) {
    const auto& c = circuits_[i];
    const std::string name = "CIRC " + std::to_string(i);
    if (!std::isfinite(c.compact_scale) || c.compact_scale < 0.0f) fail(name + " compact scale is invalid");
    if (!std::isfinite(c.compact_error) || c.compact_error < 0.0f) fail(name + " compact error is invalid");
    if (c.light_form != LightForm::Full && c.light_form != LightForm::Compact)
      fail(name + " light form " + std::to_string(std::uint32_t(c.light_form)) +
           " is neither full (0) nor compact (1)");
    if (c.light_form == LightForm::Compact && compact_intensity_.empty())
      fail(name + " is shown compact, but the bundle has no LCOL and LINT");
  }
  if (indices_.size() % 3 != 0) fail("INDX is not a whole number of triangles");
  for (std::uint32_t i : indices_)
    if (i >= vertices_.size())
      fail("INDX refers to vertex " + std::to_string(i) + " of " + std::to_string(vertices_.size()));
  for (const auto& v : vertices_)
    if (v.polygon >= polygons_.size()) fail("VERT refers to a polygon out of range");
  for (std::size_t i = 0; i < polygons_.size(); ++i) {
    const auto& p = polygons_[i];
    const std::string name = "POLY " + std::to_string(i);
    if (p.first_index % 3 != 0 || p.index_count % 3 != 0) fail(name + " index range is not whole triangles");
    if (p.first_index > indices_.size() || p.index_count > indices_.size() - p.first_index)
      fail(name + " index range runs past INDX");
    if (p.first_vertex > vertices_.size() || p.vertex_count > vertices_.size() - p.first_vertex)
      fail(name + " vertex range runs past VERT");
    if (p.material >= materials_.size()) fail(name + " material out of range");
    if (p.group >= groups_.size() && !groups_.empty()) fail(name + " group out of range");
    if (p.role > 4) fail(name + " has an unknown role");
    check_string(p.name, "POLY");
  }
  // The coarse form may only use a polygon's own vertices: the renderer's flat light is per polygon.
  if (!coarse_ranges_.empty() && coarse_ranges_.size() != polygons_.size())
    fail("CRNG must hold one range per polygon");
  if (coarse_ranges_.empty() != coarse_indices_.empty()) fail("CIDX and CRNG come together");
  for (std::size_t i = 0; i < coarse_ranges_.size(); ++i) {
    const auto& range = coarse_ranges_[i];
    const auto& p = polygons_[i];
    const std::string name = "CRNG " + std::to_string(i);
    if (range.first_index % 3 != 0 || range.index_count % 3 != 0) fail(name + " is not whole triangles");
    if (range.first_index > coarse_indices_.size() ||
        range.index_count > coarse_indices_.size() - range.first_index)
      fail(name + " runs past CIDX");
    for (std::uint32_t k = range.first_index; k < range.first_index + range.index_count; ++k)
      if (coarse_indices_[k] < p.first_vertex || coarse_indices_[k] - p.first_vertex >= p.vertex_count)
        fail(name + " refers to vertex " + std::to_string(coarse_indices_[k]) + " outside its polygon");
  }
  for (const auto& m : materials_) check_string(m.name, "MATL");
  for (const auto& g : groups_) check_string(g.name, "GRPS");
  for (const auto& c : circuits_) check_string(c.name, "CIRC");
  for (const auto& l : luminaires_) {
    check_string(l.name, "LUMS");
    if (l.circuit >= circuits_.size()) fail("LUMS refers to a circuit out of range");
  }
  validate_luminaire_shapes();
  validate_compact_codes();
  for (const auto& s : stages_) check_string(s.name, "STAG");
  if (cells_.empty()) fail("CELL is empty: a bundle has at least one cell");
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const auto& c = cells_[i];
    if (c.pvs_first > pvs_.size() || c.pvs_count > pvs_.size() - c.pvs_first)
      fail("CELL " + std::to_string(i) + " PVS range runs past PVSL");
  }
  for (std::size_t i = 0; i < portals_.size(); ++i) {
    const auto& p = portals_[i];
    const std::string name = "PORT " + std::to_string(i);
    if (p.back >= cells_.size() || p.front >= cells_.size() || p.back == p.front)
      fail(name + " joins cells out of range or a cell to itself");
    const std::uint32_t axis = p.flags & kPortalAxisMask;
    if (axis > 2 || (p.flags & ~(kPortalAxisMask | kPortalForward | kPortalBackward)) != 0)
      fail(name + " has an unknown axis or flags");
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(p.bounds_min[a]) || !std::isfinite(p.bounds_max[a]) ||
          p.bounds_min[a] > p.bounds_max[a])
        fail(name + " has a non-finite or inverted box");
  }
  for (const auto& p : leak_path_)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail("LEAK holds a non-finite point");
  for (std::size_t i = 0; i < void_facing_.size(); ++i)
    if (void_facing_[i] >= polygons_.size() || (i > 0 && void_facing_[i] <= void_facing_[i - 1]))
      fail("VOID holds a polygon out of range or out of order");
  for (std::size_t i = 0; i < cells_.size(); ++i)
    if ((cells_[i].flags & ~kCellOutside) != 0) fail("CELL " + std::to_string(i) + " has unknown flags");
  if (clusters_.empty() != cluster_polygons_.empty()) fail("CLUS and CLPO come together");
  for (std::size_t i = 0; i < clusters_.size(); ++i) {
    const auto& k = clusters_[i];
    if (k.polygon_first > cluster_polygons_.size() ||
        k.polygon_count > cluster_polygons_.size() - k.polygon_first)
      fail("CLUS " + std::to_string(i) + " polygon range runs past CLPO");
  }
  for (std::uint32_t id : cluster_polygons_)
    if (id >= polygons_.size()) fail("CLPO refers to a polygon out of range");
  if (!lod_ranges_.empty() && lod_ranges_.size() != clusters_.size() * kLodLevels)
    fail("LODR holds " + std::to_string(lod_ranges_.size()) + " records, expected " +
         std::to_string(kLodLevels) + " per cluster (" + std::to_string(clusters_.size()) + ")");
  for (std::size_t i = 0; i < lod_ranges_.size(); ++i) {
    const auto& r = lod_ranges_[i];
    if (r.first_index > lod_indices_.size() || r.index_count > lod_indices_.size() - r.first_index ||
        r.index_count % 3 != 0)
      fail("LODR " + std::to_string(i) + " index range runs past LODX or is not whole triangles");
    if (!std::isfinite(r.error) || r.error < 0.0f) fail("LODR " + std::to_string(i) + " has a bad error");
  }
  for (std::uint32_t v : lod_indices_)
    if (v >= vertices_.size()) fail("LODX refers to a vertex out of range");
  validate_textures();
  const std::size_t pvs_targets = clusters_.empty() ? polygons_.size() : clusters_.size();
  for (std::uint32_t id : pvs_)
    if (id >= pvs_targets)
      fail(clusters_.empty() ? "PVSL refers to a polygon out of range"
                             : "PVSL refers to a cluster out of range");
  const auto cell_count = static_cast<std::int64_t>(cells_.size());
  const auto node_count = static_cast<std::int64_t>(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    for (std::int32_t child : {nodes_[i].front, nodes_[i].back}) {
      // Children point forward (to a later node) or to a cell, so the tree walk always ends.
      const bool cell_ok = child < 0 && -std::int64_t(child) - 1 < cell_count;
      const bool node_ok = child > std::int64_t(i) && child < node_count;
      if (!cell_ok && !node_ok) fail("NODE " + std::to_string(i) + " has an invalid child");
    }
  }
}

std::vector<std::uint32_t> cell_polygons(const CellRecord& cell, std::span<const std::uint32_t> pvs,
                                         std::span<const ClusterRecord> clusters,
                                         std::span<const std::uint32_t> cluster_polygons) {
  const auto ids = pvs.subspan(cell.pvs_first, cell.pvs_count);
  if (clusters.empty()) return {ids.begin(), ids.end()};
  std::vector<std::uint32_t> out;
  for (const auto k : ids) {
    const auto& c = clusters[k];
    out.insert(out.end(), cluster_polygons.begin() + c.polygon_first,
               cluster_polygons.begin() + c.polygon_first + c.polygon_count);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::uint32_t> Bundle::cell_polygons(std::uint32_t cell) const {
  return model::cell_polygons(cells_[cell], pvs_, clusters_, cluster_polygons_);
}

std::uint32_t Bundle::locate_cell(const double p[3]) const {
  if (nodes_.empty()) return 0;
  std::int32_t node = 0;
  while (node >= 0) {
    const auto& n = nodes_[static_cast<std::size_t>(node)];
    const double side = n.plane[0] * p[0] + n.plane[1] * p[1] + n.plane[2] * p[2] + n.plane[3];
    node = side >= 0.0 ? n.front : n.back;
  }
  return static_cast<std::uint32_t>(-node - 1);
}

}  // namespace walk::model
