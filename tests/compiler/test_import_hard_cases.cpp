// Hard cases for import: a building 1e6 m from the origin imports to the same geometry as at the origin.
// (Nested INSERT with negative scale: test_dxf_entities.cpp; nearly degenerate brushes:
// test_quake_brushes.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/common.hpp>
#include <sstream>

#include "compiler/cleanup/cleanup.hpp"
#include "compiler/import/dxf_reader.hpp"

namespace walk::compiler {
namespace test_import_hard_cases {  // named, not anonymous: the suite compiles as unity batches

const std::string kHouse = std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf";

// The same building translated by 1e6 m in x and z and -1e6 m in y differs by less than this after import,
// clean-up and recentring (metres): doubles near 1e6 resolve 1.2e-10 m and the file prints 10 um steps, so
// the translated text is exact and 1e-9 m leaves room for one rounding in the recentring subtraction.
constexpr double kTranslatedTolerance = 1e-9;

model::Model import_recentred(const std::string& text) {
  std::istringstream in(text);
  model::Model m = read_dxf(in, "house.dxf", {}, nullptr, nullptr);
  (void)clean_up(m);
  m.origin = glm::round(bounds_of(m).centre());  // as the pipeline's recentre stage
  for (auto& p : m.polygons)
    for (auto& v : p.vertices) v -= m.origin;
  return m;
}

TEST(ImportHardCases, BuildingTranslatedByAMillionMetresImportsToTheSameGeometry) {
  std::ifstream in(kHouse);
  std::stringstream original;
  original << in.rdbuf();
  // Translate every 3DFACE corner (group codes 10..13, 20..23, 30..33) in the text itself.
  std::istringstream lines(original.str());
  std::ostringstream moved;
  std::string code, value;
  const double shift[3] = {1e6, -1e6, 1e6};
  std::size_t changed = 0;
  while (std::getline(lines, code) && std::getline(lines, value)) {
    const int c = std::atoi(code.c_str());
    if (c >= 10 && c <= 33 && c % 10 <= 3) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.5f", std::stod(value) + shift[c / 10 - 1]);
      value = buf;
      ++changed;
    }
    moved << code << "\n" << value << "\n";
  }
  ASSERT_GT(changed, 222u * 9);
  const model::Model a = import_recentred(original.str());
  const model::Model b = import_recentred(moved.str());
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(b.origin[k] - a.origin[k], shift[k]);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.polygons.size(); ++i) {
    ASSERT_EQ(a.polygons[i].vertices.size(), b.polygons[i].vertices.size());
    for (std::size_t j = 0; j < a.polygons[i].vertices.size(); ++j)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(a.polygons[i].vertices[j][k] - b.polygons[i].vertices[j][k]));
  }
  EXPECT_LT(worst, kTranslatedTolerance);
}

}  // namespace test_import_hard_cases
}  // namespace walk::compiler
