// The scene config keys the importers add: formats, `scale`, `up`, and the [plan] table, with errors that
// name the file, the line and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "compiler/scene/scene_config.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_import_config {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class ImportConfigTest : public ::testing::Test {
 protected:
  SceneConfig load(const std::string& text) {
    path_ = (fs::temp_directory_path() / ("walk_import_" + std::to_string(::getpid()) + ".toml")).string();
    std::ofstream(path_) << text;
    return load_scene_config(path_);
  }
  std::string error_of(const std::string& text) {
    try {
      (void)load(text);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  }
  void TearDown() override { fs::remove(path_); }
  std::string path_;
};

TEST_F(ImportConfigTest, FormatsFollowTheExtensionAndUpDefaultsByKind) {
  SceneConfig c = load("[model]\nfile = \"level.MAP\"\n");
  EXPECT_EQ(c.format, "map");
  EXPECT_DOUBLE_EQ(c.metres_per_unit, 0.0254);  // Quake units unless told otherwise
  EXPECT_FALSE(c.y_up);
  c = load("[model]\nfile = \"room.obj\"\nscale = 0.003\n");
  EXPECT_EQ(c.format, "obj");
  EXPECT_TRUE(c.y_up);
  EXPECT_TRUE(c.units_given);
  EXPECT_DOUBLE_EQ(c.metres_per_unit, 0.003);
  c = load("[model]\nfile = \"plan.dxf\"\nformat = \"plan\"\n");
  EXPECT_FALSE(c.units_given);  // the DXF's $INSUNITS decides
}

TEST_F(ImportConfigTest, PlanTableIsReadAndChecked) {
  const SceneConfig c = load(
      "[model]\nfile = \"plan.dxf\"\nformat = \"plan\"\nunits = \"in\"\n[plan]\nwall_height = 3.0\n"
      "door_width = [0.6, 1.8]\n[[plan.windows]]\nat = [100, 0]\nwidth = 1.5\n");
  EXPECT_DOUBLE_EQ(c.plan.wall_height, 3.0);
  EXPECT_DOUBLE_EQ(c.plan.max_door_width, 1.8);
  ASSERT_EQ(c.plan.windows.size(), 1u);
  EXPECT_DOUBLE_EQ(c.plan.windows[0].at.x, 2.54);  // drawing units to metres
  EXPECT_DOUBLE_EQ(c.plan.windows[0].width, 1.5);
}

TEST_F(ImportConfigTest, ErrorsNameFileLineAndKey) {
  std::string e = error_of("[model]\nfile = \"a.xyz\"\n");
  EXPECT_NE(e.find("supported: dxf, plan, map, obj"), std::string::npos) << e;
  e = error_of("[model]\nfile = \"a.obj\"\nunits = \"m\"\nscale = 2.0\n");
  EXPECT_NE(e.find(path_ + ":4"), std::string::npos) << e;
  EXPECT_NE(e.find("model.scale"), std::string::npos) << e;
  e = error_of("[model]\nfile = \"a.obj\"\nup = \"x\"\n");
  EXPECT_NE(e.find("model.up"), std::string::npos) << e;
  e = error_of("[model]\nfile = \"a.dxf\"\nformat = \"plan\"\n[plan]\nwall_hieght = 3.0\n");
  EXPECT_NE(e.find("wall_hieght"), std::string::npos) << e;  // unknown keys are refused
  e = error_of("[model]\nfile = \"a.dxf\"\n[plan]\nwall_height = 3.0\n");
  EXPECT_NE(e.find("only to format = \"plan\""), std::string::npos) << e;
  e = error_of(
      "[model]\nfile = \"a.dxf\"\nformat = \"plan\"\n[plan]\ndoor_height = 3.0\nwall_height = 2.5\n");
  EXPECT_NE(e.find("plan.door_height"), std::string::npos) << e;
  e = error_of("[model]\nfile = \"a.dxf\"\nformat = \"plan\"\n[[plan.windows]]\nwidth = 1.0\n");
  EXPECT_NE(e.find("at"), std::string::npos) << e;
  EXPECT_NE(e.find(path_ + ":"), std::string::npos) << e;
}

}  // namespace test_import_config
}  // namespace walk::compiler
