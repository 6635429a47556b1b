// PVS to index ranges: openings skipped, duplicates dropped, neighbours merged.
#include "render/draw_list.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "model/model.hpp"

namespace walk::render {
namespace {

std::vector<model::PolygonRecord> polygons_of(std::initializer_list<model::Role> roles) {
  std::vector<model::PolygonRecord> out;
  std::uint32_t first = 0;
  for (model::Role role : roles) {
    model::PolygonRecord p{};
    p.first_index = first;
    p.index_count = 6;
    p.role = std::uint32_t(role);
    out.push_back(p);
    first += 6;
  }
  return out;
}

TEST(DrawList, MergesNeighboursSkipsOpeningsAndSeparatesGlass) {
  using R = model::Role;
  const auto polygons = polygons_of(
      {R::Opaque, R::Opaque, R::Glass, R::Opening, R::Luminaire, R::Ignored, R::Opaque, R::Glass, R::Glass});
  const std::vector<std::uint32_t> ids{6, 0, 1, 2, 3, 4, 1, 99, 7, 8, 5};
  const DrawList list = build_draw_list(polygons, ids);
  EXPECT_EQ(list.polygons, 7u);
  EXPECT_EQ(list.triangles, 14u);
  ASSERT_EQ(list.opaque.counts.size(), 3u);  // [0,1], [4], [6]
  EXPECT_EQ(list.opaque.counts[0], 12);
  EXPECT_EQ(list.opaque.byte_offsets[0], 0u);
  EXPECT_EQ(list.opaque.counts[1], 6);
  EXPECT_EQ(list.opaque.byte_offsets[1], 24u * 4u);
  EXPECT_EQ(list.opaque.byte_offsets[2], 36u * 4u);
  ASSERT_EQ(list.glass.counts.size(), 2u);  // [2], [7,8]
  EXPECT_EQ(list.glass.byte_offsets[0], 12u * 4u);
  EXPECT_EQ(list.glass.counts[1], 12);
  EXPECT_EQ(list.glass.byte_offsets[1], 42u * 4u);
}

TEST(DrawList, AllPolygonsInOneRangeWhenNothingIsSkipped) {
  const auto polygons = polygons_of({model::Role::Opaque, model::Role::Opaque, model::Role::Glass});
  const DrawList list = build_draw_list_all(polygons);
  ASSERT_EQ(list.opaque.counts.size(), 1u);
  EXPECT_EQ(list.opaque.counts[0], 12);
  ASSERT_EQ(list.glass.counts.size(), 1u);
}

}  // namespace
}  // namespace walk::render
