// Albedo maps named by a model's materials: counted, a missing one warned about by name, and the
// material's own colour kept (textures are not drawn yet).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "compiler/import/mesh_reader.hpp"

namespace walk::compiler {
namespace {

TEST(MeshTextures, NamedTexturesAreCountedAndAMissingOneIsFoundMissing) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("walk_mesh_textures_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "box.mtl") << "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd wood.png\n"
                                 << "newmtl tile\nKd 0.8 0.8 0.8\nmap_Kd tile.png\n"
                                 << "newmtl plain\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "tile.png") << "not read, only found";
  std::ofstream(dir / "box.obj") << "mtllib box.mtl\n"
                                 << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
                                 << "usemtl wood\nf 1 2 3 4\nusemtl tile\nf 1 2 6 5\nusemtl plain\nf 1 5 4\n";
  MeshStats stats;
  const model::Model m = read_mesh((dir / "box.obj").string(), {1.0, false, 1.0}, &stats);
  EXPECT_EQ(stats.textures_named, 2u);
  EXPECT_EQ(stats.textures_missing, 1u) << "wood.png is not beside the model";
  bool wood = false;
  for (const auto& material : m.materials)
    if (material.name == "wood") {
      wood = true;
      EXPECT_NEAR(material.reflectance.r, 0.6, 1e-6) << "the material's own colour stands in";
      EXPECT_NEAR(material.reflectance.b, 0.2, 1e-6);
    }
  EXPECT_TRUE(wood);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace walk::compiler
