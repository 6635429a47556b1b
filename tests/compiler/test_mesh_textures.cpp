// Albedo maps of a model's materials: found beside the model or in the scene's folders, decoded, their mean
// carried into the reflectance the solver sees, and each face's coordinates kept as a TextureMap; a missing
// or damaged map is warned about by name and the material's own colour used.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <iterator>
#include <map>

#include "compiler/import/mesh_reader.hpp"
#include "compiler/import/texture_image.hpp"
#include "compiler/import/uv_fit.hpp"
#include "model/error.hpp"
#include "texture_files.hpp"

namespace walk::compiler {
namespace test_mesh_textures {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;
using model::Vec3;

constexpr double kExact = 1e-9;       // affine fits of exactly affine coordinates: double rounding only
constexpr double kFileColour = 1e-6;  // colours assimp reads as float: 6e-8 relative rounding

double u_at(const model::TextureMap& m, const Vec3& p) {
  return glm::dot(m.u_gradient, p) + m.u_offset;
}
double v_at(const model::TextureMap& m, const Vec3& p) {
  return glm::dot(m.v_gradient, p) + m.v_offset;
}

class TexturedModel : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_mesh_textures_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST(UvFit, TriangleIsExactAndTheFirstCornerWrapsIntoTheUnitSquare) {
  const std::vector<Vec3> corners{{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  const std::vector<glm::dvec2> uvs{{5.25, -2.5}, {6.25, -2.5}, {5.25, 0.5}};
  const auto map = fit_texture_map(corners, uvs);
  ASSERT_TRUE(map);
  // Whole repeats dropped: the first corner at (0.25, 0.5), the others moved by the same whole numbers.
  EXPECT_NEAR(u_at(*map, corners[0]), 0.25, kExact);
  EXPECT_NEAR(v_at(*map, corners[0]), 0.5, kExact);
  EXPECT_NEAR(u_at(*map, corners[1]), 1.25, kExact);
  EXPECT_NEAR(v_at(*map, corners[2]), 3.5, kExact);
  EXPECT_NEAR(u_at(*map, {1, 1.5, 0}), 0.75, kExact) << "affine inside the triangle";
}

TEST(UvFit, SlantedQuadFarFromTheOriginKeepsItsPrecision) {
  const Vec3 far(4.0e6, -3.0e6, 250.0);  // a site drawn in national grid coordinates
  const Vec3 a = glm::normalize(Vec3(1, 1, 0)), b(0, 0, 1);
  std::vector<Vec3> corners;
  std::vector<glm::dvec2> uvs;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {4.0, 0.0}, {4.0, 2.5}, {0.0, 2.5}}) {
    corners.push_back(far + a * x + b * y);
    uvs.emplace_back(0.5 * x, 0.5 * y + 0.1);
  }
  const auto map = fit_texture_map(corners, uvs);
  ASSERT_TRUE(map);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    // Relative to a corner, as the compiler uses it after recentring: millimetre-scale error would be 5e-4.
    const Vec3 shift = -far;
    model::TextureMap local = *map;
    local.translate(shift);
    EXPECT_NEAR(u_at(local, corners[i] + shift) - u_at(local, corners[0] + shift), uvs[i].x - uvs[0].x, 1e-6);
    EXPECT_NEAR(v_at(local, corners[i] + shift) - v_at(local, corners[0] + shift), uvs[i].y - uvs[0].y, 1e-6);
  }
}

TEST(UvFit, DegenerateCornersGiveNoMap) {
  const std::vector<glm::dvec2> three{{0, 0}, {1, 0}, {0, 1}};
  EXPECT_FALSE(fit_texture_map(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, three)) << "collinear";
  EXPECT_FALSE(fit_texture_map(std::vector<Vec3>{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, three)) << "one point";
  EXPECT_FALSE(fit_texture_map(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}}, {three.data(), 2})) << "two corners";
  EXPECT_FALSE(fit_texture_map(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {three.data(), 2}))
      << "coordinates missing for a corner";
  // The same coordinates at every corner are a valid map: the polygon shows one texel.
  const auto flat = fit_texture_map(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                    std::vector<glm::dvec2>{{0.3, 0.7}, {0.3, 0.7}, {0.3, 0.7}});
  ASSERT_TRUE(flat);
  EXPECT_NEAR(glm::length(flat->u_gradient), 0.0, kExact);
  EXPECT_NEAR(u_at(*flat, {0.5, 0.5, 0}), 0.3, kExact);
}

TEST(UvFit, NonAffineQuadIsTheLeastSquaresFit) {
  // A unit square whose corners' coordinates twist (u = xy is not affine): the fit is the mean plane.
  const std::vector<Vec3> corners{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::dvec2> uvs{{0, 0}, {0, 0}, {1, 0}, {0, 0}};
  const auto map = fit_texture_map(corners, uvs);
  ASSERT_TRUE(map);
  // The plane u = (x + y) / 2 - 1/4 (whole repeats aside): the corners' mean at the centre, 1/2 above corner
  // 0.
  EXPECT_NEAR(u_at(*map, {0.5, 0.5, 0}) - u_at(*map, corners[0]), 0.5, kExact);
  EXPECT_NEAR(u_at(*map, corners[2]) - u_at(*map, corners[0]), 1.0, kExact);
}

TEST_F(TexturedModel, PngDecodesBottomRowFirstWithItsLinearMean) {
  // 2 x 2, top row red and green, bottom row blue and white (mid-grey 188 -> linear 0.5029).
  test::write_test_png((dir_ / "t.png").string(), 2, 2,
                       {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 188, 188, 188, 255});
  const model::Texture t = load_texture((dir_ / "t.png").string());
  ASSERT_EQ(t.width, 2u);
  ASSERT_EQ(t.height, 2u);
  EXPECT_EQ(t.rgba[2], 255) << "first stored texel is the image's bottom-left (blue)";
  EXPECT_EQ(t.rgba[12], 0) << "last stored texel is the image's top-right (green)";
  EXPECT_EQ(t.rgba[13], 255);
  const double grey = std::pow((188 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_NEAR(t.mean.r, (1.0 + grey) / 4.0, 1e-9);
  EXPECT_NEAR(t.mean.g, (1.0 + grey) / 4.0, 1e-9);
}

TEST_F(TexturedModel, LargeTextureIsHalvedToTheLimitKeepingItsMean) {
  const std::uint32_t side = 2 * kMaxTextureSide;
  test::write_test_png((dir_ / "big.png").string(), side, 8, [&] {
    std::vector<std::uint8_t> rgba(std::size_t(side) * 8 * 4, 255);
    for (std::size_t i = 0; i < rgba.size(); i += 8) rgba[i] = rgba[i + 1] = rgba[i + 2] = 0;  // stripes
    return rgba;
  }());
  const model::Texture t = load_texture((dir_ / "big.png").string());
  EXPECT_EQ(t.width, kMaxTextureSide);
  EXPECT_EQ(t.height, 4u);
  EXPECT_NEAR(t.mean.r, 0.5, 1e-9) << "taken at full resolution";
  // Each stored texel averages a black and a white one in linear light: 0.5 -> sRGB 188.
  EXPECT_NEAR(t.rgba[0], 188, 1);
}

TEST_F(TexturedModel, DamagedOrForeignImagesAreErrorsNamingTheFile) {
  std::ofstream(dir_ / "text.png") << "not an image";
  std::ofstream(dir_ / "cut.png") << std::string("\x89PNG\r\n\x1a\n", 8) << "truncated";
  std::ofstream(dir_ / "cut.jpg") << std::string("\xFF\xD8\xFF\xE0", 4) << "truncated";
  for (const char* name : {"text.png", "cut.png", "cut.jpg", "absent.png"}) {
    const std::string path = (dir_ / name).string();
    try {
      (void)load_texture(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

TEST_F(TexturedModel, ObjMapsAreLoadedOnceFoundByFileNameOrFolderAndTheirMeanIsTheReflectance) {
  fs::create_directories(dir_ / "maps");
  test::write_test_png((dir_ / "tile.png").string(), 8, 8, test::checkerboard(8, 2));
  test::write_test_png((dir_ / "maps" / "stone.png").string(), 4, 4, test::checkerboard(4, 4));
  std::ofstream(dir_ / "box.mtl") << "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd wood.png\n"
                                  << "newmtl tile\nKd 0.8 0.8 0.8\nmap_Kd C:\\Users\\author\\tile.png\n"
                                  << "newmtl tile2\nKd 1 1 1\nmap_Kd tile.png\n"
                                  << "newmtl stone\nKd 1 0.5 1\nmap_Kd stone.png\n"
                                  << "newmtl plain\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir_ / "box.obj") << "mtllib box.mtl\n"
                                  << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
                                  << "vt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\n"
                                  << "usemtl wood\nf 1/1 2/2 3/3 4/4\nusemtl tile\nf 1/1 2/2 6/3 5/4\n"
                                  << "usemtl tile2\nf 1/1 5/2 4/3\nusemtl stone\nf 2/1 3/2 6/3\n"
                                  << "usemtl plain\nf 4 3 5\n";
  MeshStats stats;
  MeshOptions options{1.0, false, 1.0, {(dir_ / "maps").string()}};
  const model::Model m = read_mesh((dir_ / "box.obj").string(), options, &stats);
  EXPECT_EQ(stats.textures_named, 4u);
  EXPECT_EQ(stats.textures_missing, 1u) << "wood.png is nowhere";
  EXPECT_EQ(stats.textures_loaded, 2u) << "tile.png once for two materials, stone.png from the folder";
  ASSERT_EQ(m.textures.size(), 2u);
  EXPECT_EQ(stats.faces_textured, 3u);
  std::map<std::string, const model::Material*> by_name;
  for (const auto& material : m.materials) by_name[material.name] = &material;
  EXPECT_EQ(by_name.at("wood")->texture, model::kNoTexture);
  EXPECT_NEAR(by_name.at("wood")->reflectance.r, 0.6, kFileColour)
      << "the missing map's material keeps its colour";
  EXPECT_EQ(by_name.at("tile")->texture, by_name.at("tile2")->texture);
  EXPECT_NEAR(by_name.at("tile")->reflectance.g, 0.8 * 0.5, kFileColour) << "colour times the map's mean";
  EXPECT_NEAR(by_name.at("stone")->reflectance.g, 0.5 * 0.5, kFileColour);
  for (const auto& p : m.polygons) {
    const auto& material = m.materials[p.material];
    EXPECT_EQ(p.texture_map.has_value(), material.texture != model::kNoTexture) << material.name;
    if (material.name == "tile") {  // corners (0,0,0) (1,0,0) (1,0,1) (0,0,1): u = 2x, v = 2z
      EXPECT_NEAR(u_at(*p.texture_map, {0.5, 0, 0.25}), 1.0, kExact);
      EXPECT_NEAR(v_at(*p.texture_map, {0.5, 0, 0.25}), 0.5, kExact);
    }
  }
}

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= std::uint8_t(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

TEST_F(TexturedModel, GltfBaseColourTextureEmbeddedInTheFileIsDecoded) {
  test::write_test_png((dir_ / "checker.png").string(), 8, 8, test::checkerboard(8, 2));
  std::ifstream png(dir_ / "checker.png", std::ios::binary);
  const std::string png_bytes((std::istreambuf_iterator<char>(png)), {});
  const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, /* uv */ 0, 0, 1, 0, 0, 1};
  const std::string buffer(reinterpret_cast<const char*>(data), sizeof data);
  std::ofstream(dir_ / "tri.gltf")
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"name":"room"}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
      << R"("materials":[{"name":"checker","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.6,0.4,1],)"
      << R"("baseColorTexture":{"index":0}}}],"textures":[{"source":0}],)"
      << R"("images":[{"uri":"data:image/png;base64,)" << base64(png_bytes) << R"("}],)"
      << R"("buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)" << base64(buffer)
      << R"("}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)"
      << R"({"buffer":0,"byteOffset":36,"byteLength":24}],"accessors":[)"
      << R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      << R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}]})";
  MeshStats stats;
  const model::Model m = read_mesh((dir_ / "tri.gltf").string(), {1.0, true, 1.0, {}}, &stats);
  EXPECT_EQ(stats.textures_loaded, 1u);
  EXPECT_EQ(stats.textures_missing, 0u);
  EXPECT_EQ(stats.faces_textured, 1u);
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(m.textures[0].width, 8u);
  ASSERT_EQ(m.polygons.size(), 1u);
  const model::Material& material = m.materials[m.polygons[0].material];
  EXPECT_NEAR(material.reflectance.r, 0.8 * 0.5, kFileColour) << "base colour times the mean";
  EXPECT_NEAR(material.reflectance.b, 0.4 * 0.5, kFileColour);
  ASSERT_TRUE(m.polygons[0].texture_map);
  // One texture repeat along each unit edge, whichever way the file's v runs.
  const auto& map = *m.polygons[0].texture_map;
  EXPECT_NEAR(std::abs(u_at(map, m.polygons[0].vertices[1]) - u_at(map, m.polygons[0].vertices[0])), 1.0,
              1e-6);
}

TEST_F(TexturedModel, UnreadableMapIsWarnedAboutAndTheColourUsed) {
  std::ofstream(dir_ / "tile.png") << "not an image";
  std::ofstream(dir_ / "q.mtl") << "newmtl tile\nKd 0.8 0.7 0.6\nmap_Kd tile.png\n";
  std::ofstream(dir_ / "q.obj") << "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                << "usemtl tile\nf 1/1 2/2 3/3\n";
  MeshStats stats;
  const model::Model m = read_mesh((dir_ / "q.obj").string(), {1.0, false, 1.0, {}}, &stats);
  EXPECT_EQ(stats.textures_missing, 1u);
  EXPECT_TRUE(m.textures.empty());
  EXPECT_NEAR(m.materials.back().reflectance.b, 0.6, kFileColour);
  EXPECT_FALSE(m.polygons[0].texture_map);
}

}  // namespace test_mesh_textures
}  // namespace walk::compiler
