// Bundle round trip and integrity: every corruption is caught at open with a message naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "model/bundle.hpp"
#include "model/error.hpp"
#include "model/luminaire_shapes.hpp"

namespace walk::model {
namespace test_bundle {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

BundleContents small_bundle() {
  BundleContents c;
  c.meta.exposure = 2.0f;
  c.meta.ambient = 0.1f;
  c.meta.circuit_count = 2;
  c.meta.origin[0] = 1e6;  // far from the world origin: doubles keep it exact
  for (int i = 0; i < 4; ++i) {
    VertexRecord v{};
    v.position[0] = float(i & 1);
    v.position[1] = float(i >> 1);
    v.normal[2] = 1.0f;
    v.albedo[0] = v.albedo[1] = v.albedo[2] = 0.5f;
    c.vertices.push_back(v);
  }
  c.indices = {0, 1, 3, 0, 3, 2};
  c.polygons.push_back({0, 6, 0, 4, 0, 0, 0, c.add_string("floor")});
  c.materials.push_back({{0.5f, 0.5f, 0.5f}, c.add_string("default")});
  c.groups.push_back({c.add_string("room")});
  c.circuits.push_back({c.add_string("a"), 1.0f});
  c.circuits.push_back({c.add_string("b"), 0.5f});
  c.light = LightRows::from_dense(std::vector<float>(4 * 2 * 3, 0.25f), 2);
  c.cells.push_back({{0, 0, 0}, {1, 1, 0}, 0, 1});
  c.pvs = {0};
  c.stages.push_back({c.add_string("import"), 1, 42, 0.5, 1, 1});
  return c;
}

class BundleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_bundle_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    path_ = (dir_ / "x.walk").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<char> bytes() const {
    std::ifstream in(path_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  void put(const std::vector<char>& b) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
  }
  std::string open_error() const {
    try {
      Bundle::open(path_);
    } catch (const Error& e) {
      return e.what();
    }
    return {};
  }
  fs::path dir_;
  std::string path_;
};

TEST_F(BundleTest, RoundTripKeepsEveryRecord) {
  const BundleContents c = small_bundle();
  write_bundle(path_, c);
  const auto b = Bundle::open(path_);
  EXPECT_EQ(b->meta().origin[0], 1e6);
  EXPECT_EQ(b->vertices().size(), 4u);
  EXPECT_EQ(b->indices().size(), 6u);
  EXPECT_EQ(b->string(b->polygons()[0].name), "floor");
  EXPECT_EQ(b->string(b->circuits()[1].name), "b");
  EXPECT_FLOAT_EQ(b->circuits()[1].default_level, 0.5f);
  ASSERT_EQ(b->light().rows(), 4u);
  EXPECT_EQ(b->light().dense(2), std::vector<float>(24, 0.25f));
  EXPECT_EQ(b->stages()[0].input_hash, 42u);
  EXPECT_EQ(b->file_size() % kSectionAlignment, 0u);
}

TEST_F(BundleTest, OptionalLightFormsRoundTrip) {
  BundleContents c = small_bundle();
  c.compact_colour.assign(4, {200, 180, 160, 255});
  // Circuit 1 is shown compact: its codes at the four vertices (0 at the first: no light there).
  c.compact_intensity = {{0, 0, 1, 2, 3}, {1u << 8 | 10, 1u << 8 | 60, 1u << 8 | 255}};
  c.polygon_light = LightRows::from_dense(std::vector<float>{0.0f, 0.0f, 0.0f, 0.5f, 0.6f, 0.75f}, 2);
  c.circuits[1].compact_scale = 12.5f;
  c.circuits[1].light_form = LightForm::Compact;
  c.circuits[1].compact_error = 0.031f;
  write_bundle(path_, c);
  const auto b = Bundle::open(path_);
  ASSERT_EQ(b->compact_colour().size(), 4u);
  EXPECT_EQ(b->compact_colour()[3][1], 180);
  ASSERT_EQ(b->compact_intensity().rows(), 4u);
  EXPECT_TRUE(b->compact_intensity().row(0).empty());
  ASSERT_EQ(b->compact_intensity().row(3).size(), 1u);
  EXPECT_EQ(code_circuit(b->compact_intensity().row(3)[0]), 1u);
  EXPECT_EQ(code_value(b->compact_intensity().row(3)[0]), 255);
  ASSERT_EQ(b->polygon_light().rows(), 1u);
  ASSERT_EQ(b->polygon_light().row(0).size(), 1u);  // circuit 0's zeros are left out
  EXPECT_EQ(b->polygon_light().row(0)[0].circuit, 1u);
  EXPECT_FLOAT_EQ(b->polygon_light().row(0)[0].rgb[2], 0.75f);
  EXPECT_FLOAT_EQ(b->circuits()[1].compact_scale, 12.5f);
  EXPECT_EQ(b->circuits()[1].light_form, LightForm::Compact);
  EXPECT_EQ(b->circuits()[0].light_form, LightForm::Full);
  EXPECT_FLOAT_EQ(b->circuits()[1].compact_error, 0.031f);

  // A light form that is neither, and a compact circuit without the compact form: refused, naming it.
  c.circuits[0].light_form = LightForm(7);
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CIRC 0 light form 7"), std::string::npos) << open_error();
  c.circuits[0].light_form = LightForm::Full;
  const CompactCodes codes = c.compact_intensity;
  c.compact_colour.clear();
  c.compact_intensity = {};
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CIRC 1 is shown compact"), std::string::npos) << open_error();
  c.compact_colour.assign(4, {200, 180, 160, 255});
  c.compact_intensity = codes;
  c.compact_intensity.first.pop_back();  // one row short: refused, naming the section
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LINT has 3 rows"), std::string::npos) << open_error();
  c.compact_intensity = codes;
  c.compact_intensity.codes[0] = 0u << 8 | 10;  // a code of circuit 0, which is shown full
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LINT row 1 holds a code of circuit 0"), std::string::npos) << open_error();
  c.compact_intensity = codes;
  c.compact_intensity.codes[1] = 1u << 8;  // code 0: no light, which LINT leaves out
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("zero"), std::string::npos) << open_error();
}

TEST_F(BundleTest, CoarseFormRoundTripsAndStaysInsideItsPolygon) {
  BundleContents c = small_bundle();
  c.coarse_indices = {0, 1, 3, 0, 3, 2};
  c.coarse_ranges = {{0, 6}};
  write_bundle(path_, c);
  const auto b = Bundle::open(path_);
  ASSERT_EQ(b->coarse_ranges().size(), 1u);
  EXPECT_EQ(b->coarse_ranges()[0].index_count, 6u);
  EXPECT_EQ(b->coarse_indices()[2], 3u);

  c.polygons[0].vertex_count = 3;  // vertex 3 now lies outside the polygon that draws it
  c.indices = {0, 1, 2, 0, 2, 1};
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CRNG 0 refers to vertex 3 outside its polygon"), std::string::npos)
      << open_error();

  c = small_bundle();
  c.coarse_indices = {0, 1, 3, 0, 3, 2};
  c.coarse_ranges = {{3, 6}};  // past the end of CIDX
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CRNG 0 runs past CIDX"), std::string::npos) << open_error();

  c.coarse_ranges.clear();  // indices without ranges
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CIDX and CRNG come together"), std::string::npos) << open_error();
}

TEST_F(BundleTest, EveryFlippedByteIsRejected) {
  write_bundle(path_, small_bundle());
  const std::vector<char> good = bytes();
  // Flip one bit in every byte that carries data (padding bytes are not covered by checksums, so skip zeros
  // between sections by checking that the flip changes what a reader would see: the open must fail or the
  // byte lies in padding).
  std::size_t rejected = 0, padding = 0;
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::vector<char> bad = good;
    bad[i] ^= 0x10;
    put(bad);
    const std::string err = open_error();
    if (err.empty()) {
      ++padding;
      continue;
    }
    ++rejected;
    EXPECT_NE(err.find(path_), std::string::npos) << err;
  }
  EXPECT_GT(rejected, good.size() / 2);
  // What was accepted must be alignment padding only: at most 15 bytes per section boundary plus the tail.
  EXPECT_LE(padding, 16u * 15u);
}

TEST_F(BundleTest, TruncatedFileIsRejected) {
  write_bundle(path_, small_bundle());
  std::vector<char> b = bytes();
  for (std::size_t keep : {std::size_t(0), std::size_t(10), std::size_t(40), b.size() / 2, b.size() - 1}) {
    put(std::vector<char>(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(keep)));
    EXPECT_NE(open_error(), "") << "kept " << keep << " bytes";
  }
}

TEST_F(BundleTest, CrossReferencesAreValidated) {
  BundleContents c = small_bundle();
  c.indices[2] = 99;  // vertex out of range, with a correct checksum
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("INDX"), std::string::npos);

  c = small_bundle();
  c.cells[0].pvs_count = 5;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("PVS"), std::string::npos);

  c = small_bundle();
  c.light.entries[3].rgb[0] = -1.0f;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LGHT"), std::string::npos);

  // Sparse rows that name a circuit twice, out of range, or do not span their entries.
  c = small_bundle();
  c.light.entries[1].circuit = 0;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LGHT row 0 names circuit 0 out of order"), std::string::npos) << open_error();
  c = small_bundle();
  c.light.entries[1].circuit = 2;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("out of range"), std::string::npos);
  c = small_bundle();
  c.light.first.back() = 7;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LGHT row starts"), std::string::npos);
  c = small_bundle();
  c.light.first.pop_back();
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LGHT has 3 rows, expected 4"), std::string::npos) << open_error();

  c = small_bundle();
  c.nodes.push_back({{1, 0, 0, 0}, 0, -1});  // a node pointing at itself would loop forever
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("NODE"), std::string::npos);
}

TEST_F(BundleTest, ClustersExpandToTheirPolygonsAndAreValidated) {
  BundleContents c = small_bundle();
  c.clusters.push_back({{0, 0, 0}, {1, 1, 0}, 0, 1});
  c.cluster_polygons = {0};
  c.cells[0].flags = kCellOutside;
  c.leak_path = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.5f, 0.0f}};
  write_bundle(path_, c);
  {
    const auto b = Bundle::open(path_);
    ASSERT_EQ(b->clusters().size(), 1u);
    EXPECT_EQ(b->cell_polygons(0), std::vector<std::uint32_t>{0});
    EXPECT_EQ(b->cells()[0].flags, kCellOutside);
    EXPECT_EQ(b->leak_path().size(), 2u);
  }
  c.clusters[0].polygon_count = 2;  // runs past CLPO
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CLUS"), std::string::npos);
  c = small_bundle();
  c.clusters.push_back({{0, 0, 0}, {1, 1, 0}, 0, 1});
  c.cluster_polygons = {7};  // no such polygon
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("CLPO"), std::string::npos);
  c.cluster_polygons = {0};
  c.pvs = {1};  // no such cluster
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("cluster out of range"), std::string::npos);
  c = small_bundle();
  c.cells[0].flags = 6;
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("flags"), std::string::npos);
  c = small_bundle();
  c.leak_path = {{std::nanf(""), 0.0f, 0.0f}};
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LEAK"), std::string::npos);
}

TEST_F(BundleTest, PortalsAreReadAndValidated) {
  BundleContents c = small_bundle();
  c.cells.push_back(c.cells[0]);  // two cells, split at x = 0.5
  c.nodes = {{{1, 0, 0, -0.5}, -2, -1}};
  c.portals = {{{0.5f, 0.0f, 0.0f}, {0.5f, 1.0f, 1.0f}, 0, 1, 0 | kPortalForward | kPortalBackward, 0}};
  write_bundle(path_, c);
  {
    const auto b = Bundle::open(path_);
    ASSERT_EQ(b->portals().size(), 1u);
    EXPECT_EQ(b->portals()[0].front, 1u);
  }
  auto broken = [&](auto&& change, const char* what) {
    BundleContents d = c;
    change(d.portals[0]);
    write_bundle(path_, d);
    const std::string error = open_error();
    EXPECT_NE(error.find("PORT 0"), std::string::npos) << what << ": " << error;
  };
  broken([](PortalRecord& p) { p.front = 2; }, "a cell out of range");
  broken([](PortalRecord& p) { p.front = 0; }, "a cell joined to itself");
  broken([](PortalRecord& p) { p.flags = 3; }, "axis 3");
  broken([](PortalRecord& p) { p.flags |= 16; }, "an unknown flag");
  broken([](PortalRecord& p) { p.bounds_max[1] = std::nanf(""); }, "a NaN corner");
  broken([](PortalRecord& p) { p.bounds_min[2] = 2.0f; }, "an inverted box");
}

TEST_F(BundleTest, LuminaireShapesAndDistributionsRoundTripAndAreValidated) {
  BundleContents c = small_bundle();
  auto table = std::make_shared<IntensityDistribution>();
  table->gamma_deg = {0, 90, 180};
  table->c_deg = {0, 180, 360};
  table->candela = {10, 5, 0, 20, 10, 0, 10, 5, 0};
  table->lumens = 50.0;
  std::vector<Luminaire> lights(3);
  lights[0].kind = LuminaireKind::Area;
  lights[1].kind = LuminaireKind::Spot;
  lights[1].cone = 0.5;
  lights[1].exponent = 4.0;
  lights[2].kind = LuminaireKind::Photometric;
  lights[2].distribution = table;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    c.luminaires.push_back({});
    c.luminaires.back().name = c.add_string("l");
  }
  store_luminaire_shapes(lights, c);
  write_bundle(path_, c);
  {
    const auto b = Bundle::open(path_);
    const auto back = load_luminaires(*b);
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back[1].kind, LuminaireKind::Spot);
    EXPECT_FLOAT_EQ(static_cast<float>(back[1].exponent), 4.0f);
    ASSERT_TRUE(back[2].distribution);
    EXPECT_DOUBLE_EQ(back[2].distribution->candela_at(45, 90), 0.5 * (7.5 + 15.0));  // bilinear
    EXPECT_DOUBLE_EQ(back[2].distribution->lumens, 50.0);
  }
  auto broken = [&](auto&& change, const char* what, const char* expected) {
    BundleContents d = c;
    change(d);
    write_bundle(path_, d);
    const std::string error = open_error();
    EXPECT_NE(error.find(expected), std::string::npos) << what << ": " << error;
  };
  broken([](BundleContents& d) { d.luminaire_shapes[0].kind = 9; }, "an unknown kind", "LMSH 0");
  broken([](BundleContents& d) { d.luminaire_shapes[2].distribution = 1; }, "a table out of range", "LMSH 2");
  broken([](BundleContents& d) { d.luminaire_shapes[1].distribution = 0; }, "a spot with a table", "LMSH 1");
  broken([](BundleContents& d) { d.luminaire_shapes.pop_back(); }, "one short", "LMSH holds 2");
  broken([](BundleContents& d) { d.distributions[0].c_count = 4; }, "a table past DSTV", "DIST 0");
  broken([](BundleContents& d) { d.distribution_values[4] = -1.0f; }, "a negative candela", "DSTV");
}

TEST_F(BundleTest, LevelsOfDetailAreReadAndValidated) {
  BundleContents c = small_bundle();
  c.clusters.push_back({{0, 0, 0}, {1, 1, 0}, 0, 1});
  c.cluster_polygons = {0};
  c.lod_indices = {0, 1, 2};
  c.lod_ranges = {{0, 3, 0.05f, 0}, {0, 0, 0.0f, 0}, {0, 0, 0.0f, 0}};
  write_bundle(path_, c);
  {
    const auto b = Bundle::open(path_);
    ASSERT_EQ(b->lod_ranges().size(), kLodLevels);
    EXPECT_FLOAT_EQ(b->lod_ranges()[0].error, 0.05f);
    EXPECT_EQ(b->lod_indices().size(), 3u);
  }
  c.lod_ranges.pop_back();  // not kLodLevels per cluster
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LODR holds 2 records"), std::string::npos);
  c.lod_ranges.push_back({0, 6, 0.0f, 0});  // runs past LODX
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LODR 2"), std::string::npos);
  c.lod_ranges.back() = {0, 0, -1.0f, 0};
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("bad error"), std::string::npos);
  c.lod_ranges.back() = {0, 0, 0.0f, 0};
  c.lod_indices = {0, 1, 99};
  write_bundle(path_, c);
  EXPECT_NE(open_error().find("LODX"), std::string::npos);
}

TEST_F(BundleTest, AlbedoMapsAreReadAndValidated) {
  BundleContents c = small_bundle();
  c.textures.push_back({2, 1, 0, {0.5f, 0.25f, 0.125f}, c.add_string("checker.png")});
  c.texels.assign(2 * 1 * 4, 128);
  c.polygon_textures.assign(c.polygons.size(), {{0.5f, 0, 0, 0}, {0, 0.5f, 0, 0}, 0});
  write_bundle(path_, c);
  {
    const auto b = Bundle::open(path_);
    ASSERT_EQ(b->textures().size(), 1u);
    EXPECT_EQ(b->string(b->textures()[0].name), "checker.png");
    EXPECT_EQ(b->texels().size(), 8u);
    EXPECT_FLOAT_EQ(b->polygon_textures()[0].u[0], 0.5f);
  }
  const auto expect_error = [&](const BundleContents& damaged, const char* what) {
    write_bundle(path_, damaged);
    const std::string err = open_error();
    EXPECT_NE(err.find(what), std::string::npos) << err;
  };
  BundleContents d = c;
  d.polygon_textures[0].texture = 1;
  expect_error(d, "PTEX 0 refers to a texture out of range");
  d = c;
  d.polygon_textures[0].v[3] = std::numeric_limits<float>::infinity();
  expect_error(d, "PTEX 0 has a non-finite coordinate");
  d = c;
  d.polygon_textures.push_back(d.polygon_textures.back());
  expect_error(d, "PTEX holds");
  d = c;
  d.texels.resize(4);
  expect_error(d, "TEXR 0 is empty or its texels run past TEXL");
  d = c;
  d.textures[0].mean[1] = 0.0f;
  expect_error(d, "TEXR 0 has a bad mean");
  d = c;
  d.polygon_textures.clear();
  expect_error(d, "TEXR and PTEX come together");
  // No texture but a polygon record saying "none" is fine: a scene where only some polygons have maps.
  d = c;
  d.polygon_textures[0].texture = kNoTextureRecord;
  write_bundle(path_, d);
  EXPECT_NO_THROW((void)Bundle::open(path_));
}

TEST_F(BundleTest, AFolderIsNamedAsOne) {
  const std::string folder = (dir_ / "scene.walk").string();
  std::filesystem::create_directories(folder);
  try {
    (void)Bundle::open(folder);
    ADD_FAILURE() << "a folder opened as a bundle";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

TEST_F(BundleTest, AnOlderFormatNamesItsVersionAndTheFix) {
  write_bundle(path_, small_bundle());
  std::vector<char> b = bytes();
  const std::uint32_t old = kBundleVersion - 1;
  std::memcpy(b.data() + 8, &old, sizeof old);  // FileHeader::version follows the 8-byte magic
  put(b);
  const std::string err = open_error();
  EXPECT_NE(err.find("version " + std::to_string(old)), std::string::npos) << err;
  EXPECT_NE(err.find("walk compile"), std::string::npos) << err;
}

TEST_F(BundleTest, FailedWriteLeavesNoFile) {
  const std::string inside_missing = (dir_ / "no_such_folder" / "x.walk").string();
  EXPECT_THROW(write_bundle(inside_missing, small_bundle()), Error);
  EXPECT_FALSE(fs::exists(inside_missing));
  write_bundle(path_, small_bundle());
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u) << "temporary file left behind";
}

TEST_F(BundleTest, MissingFileNamesTheCommandToRun) {
  const std::string err = open_error();
  EXPECT_NE(err.find("walk compile"), std::string::npos) << err;
}

TEST_F(BundleTest, LocateCellWalksTheTree) {
  BundleContents c = small_bundle();
  c.cells.push_back({{0, 0, 0}, {1, 1, 0}, 0, 1});
  c.nodes.push_back({{1, 0, 0, -0.5}, -2, -1});  // x >= 0.5: cell 1, else cell 0
  write_bundle(path_, c);
  const auto b = Bundle::open(path_);
  const double left[3] = {0.2, 0.5, 0}, right[3] = {0.8, 0.5, 0}, on_plane[3] = {0.5, 0.5, 0};
  EXPECT_EQ(b->locate_cell(left), 0u);
  EXPECT_EQ(b->locate_cell(right), 1u);
  EXPECT_EQ(b->locate_cell(on_plane), 1u);  // ties go to the front side
}

}  // namespace test_bundle
}  // namespace walk::model
