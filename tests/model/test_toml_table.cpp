// The one TOML accessor (scene and kiosk configs): typed reads, fallbacks, ranges, and errors that name the
// file, line and dotted key.
#include <gtest/gtest.h>

#include <functional>

#include "model/error.hpp"
#include "model/toml_table.hpp"

namespace walk {
namespace test_toml_table {  // named, not anonymous: the suite compiles as unity batches

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TomlTable, RangedReadsTakeFallbacksAndNameKeyAndBounds) {
  const toml::table root = toml::parse("[display]\nwidth = 1280\nhz = 600.0\nfull = true\nname = 3\n");
  const TomlTable top(root, "kiosk.toml", "");
  const auto display = top.table("display");
  ASSERT_TRUE(display);
  EXPECT_EQ(display->integer("width", 640, 16, 16384), 1280);
  EXPECT_EQ(display->integer("height", 720, 16, 16384), 720);  // missing: the fallback
  EXPECT_TRUE(display->boolean("full", false));
  EXPECT_FALSE(display->boolean("stereo", false));
  EXPECT_DOUBLE_EQ(display->number("fov", 60.0, 10.0, 150.0), 60.0);
  const std::string hz = error_of([&] { (void)display->number("hz", 60.0, 1.0, 480.0); });
  EXPECT_NE(hz.find("kiosk.toml:3: key 'display.hz': must be between 1 and 480"), std::string::npos) << hz;
  const std::string width = error_of([&] { (void)display->integer("width", 0, 16, 1024); });
  EXPECT_NE(width.find(":2: key 'display.width': must be between 16 and 1024"), std::string::npos) << width;
  const std::string name = error_of([&] { (void)display->string("name"); });
  EXPECT_NE(name.find("key 'display.name': expected a string"), std::string::npos) << name;
  const std::string whole = error_of([&] { (void)display->integer("hz", 0, 0, 1000); });
  EXPECT_NE(whole.find("expected an integer"), std::string::npos) << whole;
}

TEST(TomlTable, FailWithoutAKeyNamesTheTableOrJustTheProblem) {
  const toml::table root = toml::parse("a = 1\n\n[start]\nx = 1\n");
  const TomlTable top(root, "kiosk.toml", "");
  const std::string bare = error_of([&] { top.fail("", "missing table [walker]"); });
  EXPECT_NE(bare.find("kiosk.toml"), std::string::npos) << bare;
  EXPECT_NE(bare.find(": missing table [walker]"), std::string::npos) << bare;
  EXPECT_EQ(bare.find("key ''"), std::string::npos) << bare;
  const std::string start = error_of([&] { top.table("start")->fail("", "needs floor_z or eye_z"); });
  EXPECT_NE(start.find("kiosk.toml:3: key 'start': needs floor_z or eye_z"), std::string::npos) << start;
  const std::string unknown = error_of([&] { top.only({"b"}); });
  EXPECT_NE(unknown.find("kiosk.toml:1: unknown key 'a'"), std::string::npos) << unknown;
}

}  // namespace test_toml_table
}  // namespace walk
