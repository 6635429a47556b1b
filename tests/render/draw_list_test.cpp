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

TEST(DrawList, MergesNeighboursAndSkipsOpenings) {
  using R = model::Role;
  const auto polygons = polygons_of({R::Opaque, R::Glass, R::Opening, R::Luminaire, R::Ignored, R::Opaque});
  const std::vector<std::uint32_t> ids{5, 0, 1, 2, 3, 1, 99};
  const DrawList list = build_draw_list(polygons, ids);
  EXPECT_EQ(list.polygons, 4u);
  EXPECT_EQ(list.triangles, 8u);
  ASSERT_EQ(list.counts.size(), 3u);  // [0,1], [3], [5]
  EXPECT_EQ(list.counts[0], 12);
  EXPECT_EQ(list.byte_offsets[0], 0u);
  EXPECT_EQ(list.counts[1], 6);
  EXPECT_EQ(list.byte_offsets[1], 18u * 4u);
  EXPECT_EQ(list.byte_offsets[2], 30u * 4u);
}

TEST(DrawList, AllPolygonsInOneRangeWhenNothingIsSkipped) {
  const auto polygons = polygons_of({model::Role::Opaque, model::Role::Opaque, model::Role::Glass});
  const DrawList list = build_draw_list_all(polygons);
  ASSERT_EQ(list.counts.size(), 1u);
  EXPECT_EQ(list.counts[0], 18);
}

}  // namespace
}  // namespace walk::render
