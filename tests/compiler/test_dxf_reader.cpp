// DXF import on the real EnergyPlus exports in shared data, plus tiny hand-made bad inputs.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include "compiler/import/dxf_reader.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_dxf_reader {  // named, not anonymous: the suite compiles as unity batches

const std::string kOffice = std::string(WALK_SHARED_DATA) + "/eplus-medium-office/refbldg_medium_office.dxf";
const std::string kHouse = std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf";
const std::string kData = std::string(WALK_SOURCE_DIR) + "/tests/compiler/data/";

// Counted straight from the text, independently of the reader.
std::size_t count_lines_equal(const std::string& path, const std::string& text) {
  std::ifstream in(path);
  std::string line;
  std::size_t count = 0;
  while (std::getline(in, line)) count += line == text ? 1 : 0;
  return count;
}

std::string error_of(const std::string& path) {
  try {
    (void)read_dxf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(DxfReader, MediumOfficeCountsColoursAndBounds) {
  DxfStats stats;
  const model::Model m = read_dxf(kOffice, {}, &stats);
  const std::size_t faces_in_file = count_lines_equal(kOffice, "3DFACE");
  ASSERT_EQ(faces_in_file, 146u);
  EXPECT_EQ(m.polygons.size(), faces_in_file);
  EXPECT_EQ(stats.faces, faces_in_file);
  EXPECT_EQ(stats.degenerate, 0u);
  EXPECT_EQ(stats.skipped.at("TEXT"), count_lines_equal(kOffice, "TEXT"));
  EXPECT_EQ(m.groups.size(), 19u);  // 18 zones + layer "1" (north arrow)
  ASSERT_EQ(m.materials.size(), 1u);

  std::map<int, std::size_t> colours;
  model::Bounds building;
  std::size_t arrow = 0;
  for (const auto& p : m.polygons) {
    EXPECT_EQ(p.role, model::Role::Opaque);
    EXPECT_EQ(p.material, 0u);
    EXPECT_EQ(p.vertices.size(), 4u);  // no triangulated faces in this file
    EXPECT_GT(p.source_line, 0u);
    if (m.groups[p.group] == "1") {
      ++arrow;
      continue;
    }
    EXPECT_NE(p.name.find(':'), std::string::npos) << p.name;
    ++colours[p.color];
    for (const auto& v : p.vertices) building.add(v);
  }
  EXPECT_EQ(arrow, 6u);
  EXPECT_EQ(colours[43], 72u);
  EXPECT_EQ(colours[8], 30u);
  EXPECT_EQ(colours[15], 26u);
  EXPECT_EQ(colours[143], 12u);
  EXPECT_NEAR(building.min.x, 0.0, 1e-3);
  EXPECT_NEAR(building.min.y, 0.0, 1e-3);
  EXPECT_NEAR(building.min.z, 0.0, 1e-3);
  EXPECT_NEAR(building.max.x, 49.911, 1e-3);
  EXPECT_NEAR(building.max.y, 33.274, 1e-3);
  EXPECT_NEAR(building.max.z, 11.887, 1e-3);
}

TEST(DxfReader, MediumOfficeSourceLinePointsAtEntity) {
  const model::Model m = read_dxf(kOffice);
  std::ifstream in(kOffice);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (const auto& p : m.polygons) {
    ASSERT_LT(p.source_line, lines.size());
    EXPECT_EQ(lines[p.source_line - 1], "  0");  // the entity's 0 code...
    EXPECT_EQ(lines[p.source_line], "3DFACE");   // ...followed by its type
  }
}

TEST(DxfReader, HouseDoorsWindowsHolesAndTriangles) {
  DxfStats stats;
  const model::Model m = read_dxf(kHouse, {}, &stats);
  ASSERT_EQ(count_lines_equal(kHouse, "3DFACE"), 222u);
  EXPECT_EQ(m.polygons.size() + stats.degenerate, 222u);
  EXPECT_EQ(stats.skipped.at("TEXT"), 2u);
  EXPECT_EQ(m.groups.size(), 18u);  // 16 zones + "Building Shading" + "1"
  std::size_t doors = 0, glazing = 0, win = 0, hole = 0, triangles = 0;
  for (const auto& p : m.polygons) {
    if (p.vertices.size() == 3) ++triangles;
    if (p.color == 45) ++doors;
    if (p.color == 143) {
      ++glazing;
      if (ends_with(p.name, "_WIN")) ++win;
      if (p.name.find("_HOLE") != std::string::npos) ++hole;
    }
  }
  EXPECT_EQ(doors, 17u);
  EXPECT_EQ(glazing, 32u);
  EXPECT_EQ(win, 25u);
  EXPECT_EQ(hole, 7u);
  EXPECT_EQ(triangles, stats.triangles);
  EXPECT_GE(triangles, 16u);  // the TRIANGULATE3DFACE'd floors (north arrow faces may add some)
}

TEST(DxfReader, UnitScaleApplies) {
  const model::Model metres = read_dxf(kData + "small.dxf");
  const model::Model millimetres = read_dxf(kData + "small.dxf", DxfOptions{0.001});
  ASSERT_EQ(metres.polygons.size(), millimetres.polygons.size());
  EXPECT_DOUBLE_EQ(millimetres.polygons[0].vertices[1].x, 0.004);
  EXPECT_DOUBLE_EQ(metres.polygons[0].vertices[1].x, 4.0);
}

TEST(DxfReader, SmallFixtureFacesTrianglesAndDegenerates) {
  DxfStats stats;
  const model::Model m = read_dxf(kData + "small.dxf", {}, &stats);
  ASSERT_EQ(m.polygons.size(), 2u);
  EXPECT_EQ(stats.degenerate, 1u);
  EXPECT_EQ(stats.triangles, 1u);
  EXPECT_EQ(stats.skipped.at("TEXT"), 1u);
  EXPECT_EQ(m.polygons[0].name, "Z1:WALL_1");
  EXPECT_EQ(m.polygons[0].color, 43);
  EXPECT_EQ(m.polygons[0].source_line, 21u);
  EXPECT_EQ(m.groups[m.polygons[0].group], "Z1");
  EXPECT_EQ(m.polygons[1].vertices.size(), 3u);
  EXPECT_EQ(m.polygons[1].source_line, 53u);
}

TEST(DxfReader, WindowsLineEndingsReadTheSame) {
  const model::Model unix_lines = read_dxf(kData + "small.dxf");
  const model::Model crlf = read_dxf(kData + "small_crlf.dxf");
  ASSERT_EQ(crlf.polygons.size(), unix_lines.polygons.size());
  for (std::size_t i = 0; i < crlf.polygons.size(); ++i) {
    EXPECT_EQ(crlf.polygons[i].vertices, unix_lines.polygons[i].vertices);
    EXPECT_EQ(crlf.polygons[i].name, unix_lines.polygons[i].name);
    EXPECT_EQ(crlf.groups[crlf.polygons[i].group], unix_lines.groups[unix_lines.polygons[i].group]);
  }
}

TEST(DxfReader, TriangulatedSurfacesKeepTheirName) {
  // EnergyPlus writes one 999 comment before the first triangle of a TRIANGULATE3DFACE'd surface only.
  const model::Model m = read_dxf(kHouse);
  for (const auto& p : m.polygons) {
    if (m.groups[p.group] == "1") continue;
    EXPECT_NE(p.name.find(':'), std::string::npos) << "line " << p.source_line << ": " << p.name;
    EXPECT_EQ(p.name.substr(0, p.name.find(':')), m.groups[p.group]) << "line " << p.source_line;
  }
}

TEST(DxfReader, BadUnitScaleIsAnError) {
  try {
    (void)read_dxf(kData + "small.dxf", DxfOptions{0.0});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unit scale"), std::string::npos) << e.what();
  }
}

TEST(DxfReader, EmptyFileIsAnError) {
  const std::string message = error_of(kData + "empty_file.dxf");
  EXPECT_NE(message.find("empty_file.dxf: the DXF file is empty"), std::string::npos) << message;
}

TEST(DxfReader, MissingFileNamesIt) {
  const std::string message = error_of(kData + "no_such_file.dxf");
  EXPECT_NE(message.find("no_such_file.dxf"), std::string::npos) << message;
  EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
}

TEST(DxfReader, OddLineCountIsTruncation) {
  const std::string message = error_of(kData + "truncated_pair.dxf");
  EXPECT_NE(message.find("truncated_pair.dxf:35:"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST(DxfReader, EntityCutOffIsTruncation) {
  const std::string message = error_of(kData + "truncated_entity.dxf");
  EXPECT_NE(message.find("truncated_entity.dxf:50:"), std::string::npos) << message;
  EXPECT_NE(message.find("EOF"), std::string::npos) << message;
  EXPECT_NE(message.find("entity at line 39"), std::string::npos) << message;
}

TEST(DxfReader, NonNumericCoordinateNamesValueLine) {
  const std::string message = error_of(kData + "bad_coordinate.dxf");
  EXPECT_NE(message.find("bad_coordinate.dxf:48:"), std::string::npos) << message;
  EXPECT_NE(message.find("3.0O"), std::string::npos) << message;
}

TEST(DxfReader, NonNumericGroupCodeNamesItsLine) {
  const std::string message = error_of(kData + "bad_group_code.dxf");
  EXPECT_NE(message.find("bad_group_code.dxf:13:"), std::string::npos) << message;
}

TEST(DxfReader, MissingCornerNamesEntityLine) {
  const std::string message = error_of(kData + "missing_corner.dxf");
  EXPECT_NE(message.find("missing_corner.dxf:39:"), std::string::npos) << message;
  EXPECT_NE(message.find("corner 3"), std::string::npos) << message;
}

TEST(DxfReader, EmptyModelIsAnError) {
  const std::string message = error_of(kData + "empty_model.dxf");
  EXPECT_NE(message.find("empty_model.dxf"), std::string::npos) << message;
  EXPECT_NE(message.find("no usable 3DFACE"), std::string::npos) << message;
}

}  // namespace test_dxf_reader
}  // namespace walk::compiler
