// The still view's diagonals and sub-quads made unit by unit (render/unit_refinement.hpp) against the same
// choice over the whole model at once: the units asked for get exactly the whole model's indices and
// sub-quads, the others keep the bundle's, and a unit is made once per mix.
#include "render/unit_refinement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <limits>
#include <numeric>
#include <vector>

#include "model/model.hpp"
#include "render/cluster_layout.hpp"
#include "render/diagonals.hpp"
#include "render/subdivision.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace unit_refinement_test {  // named, not anonymous: the suite compiles as unity batches

struct Fixture {
  std::unique_ptr<model::Bundle> bundle;
  ClusterLayout layout;
  std::vector<float> levels;
  std::vector<glm::vec3> colour;  // per vertex: a field that curves across each quad, so diagonals differ
};

Fixture rooms(const std::vector<float>& levels) {
  TwoRooms scene;
  scene.subdivisions = 4;
  Fixture f;
  f.bundle = open_two_rooms(scene, "unit_refinement");
  f.layout = lay_out_clusters(layout_input(*f.bundle));
  f.levels = levels;
  for (const model::VertexRecord& v : f.bundle->vertices()) {
    const glm::vec3 p(v.position[0], v.position[1], v.position[2]);
    const float wave = std::sin(2.3f * p.x + 1.7f * p.y + 2.9f * p.z) + 0.4f * p.x * p.z;
    f.colour.push_back(glm::vec3(1.0f + 0.5f * wave, 1.0f - 0.3f * wave, 1.0f));
  }
  return f;
}

RefinementInput input_of(const Fixture& f) {
  return {f.layout.fine.polygons, f.layout.unit_of_polygon, f.layout.units(), f.bundle->vertices(),
          f.layout.fine.indices};
}

// The unit's index ranges in the fine form, copied out of `indices`.
std::vector<std::uint32_t> unit_indices(const Fixture& f, std::uint32_t u,
                                        const std::vector<std::uint32_t>& indices) {
  std::vector<std::uint32_t> out;
  for (const IndexRange& r : {f.layout.fine.opaque[u], f.layout.fine.glass[u]})
    out.insert(out.end(), indices.begin() + r.first, indices.begin() + r.first + r.count);
  return out;
}

TEST(UnitRefinement, UnitsMadeAloneEqualTheWholeModelsChoice) {
  const Fixture f = rooms({1.0f, 0.7f});
  constexpr float kThreshold = 0.01f;  // displayed radiosity: the rooms' light is about 1
  constexpr int kDepth = 3;
  // The whole model at once, as the renderer chose before units.
  const auto vertices = f.bundle->vertices();
  const std::vector<Quad> quads = find_quads(f.layout.fine.polygons, f.layout.fine.indices, vertices);
  std::vector<std::uint32_t> whole = f.layout.fine.indices;
  const std::size_t flipped = choose_diagonals(quads, f.colour, whole);
  std::vector<Quad> opaque;
  for (const Quad& q : quads)
    if (f.layout.fine.polygons[q.polygon].role != std::uint32_t(model::Role::Glass)) opaque.push_back(q);
  const Subdivision sub = subdivide(opaque, vertices, f.colour, kThreshold, kDepth);
  ASSERT_GT(flipped, 0u);
  ASSERT_GT(sub.replaced_quads.size(), 0u);

  std::vector<std::uint32_t> all(f.layout.units());
  std::iota(all.begin(), all.end(), 0u);
  const std::vector<std::uint32_t> first_half(all.begin(), all.begin() + std::ptrdiff_t(all.size() / 2));
  const std::vector<std::uint32_t> second_half(all.begin() + std::ptrdiff_t(all.size() / 2), all.end());
  UnitRefinement refinement(input_of(f));
  std::vector<std::uint32_t> indices = f.layout.fine.indices;
  int calls = 0;
  const auto colour_of = [&](std::uint32_t v) {
    ++calls;
    return f.colour[v];
  };
  const RefinementKey key{f.levels, kThreshold, kDepth};
  EXPECT_EQ(refinement.update(first_half, key, colour_of, indices).made, first_half);
  for (const std::uint32_t u : first_half)
    EXPECT_EQ(unit_indices(f, u, indices), unit_indices(f, u, whole)) << u;
  for (const std::uint32_t u : second_half)
    EXPECT_EQ(unit_indices(f, u, indices), unit_indices(f, u, f.layout.fine.indices)) << "not asked: " << u;
  const int first_calls = calls;
  EXPECT_GT(first_calls, 0);
  EXPECT_LT(first_calls, int(4 * quads.size())) << "only the first half's vertices are coloured";

  EXPECT_TRUE(refinement.update(first_half, key, colour_of, indices).made.empty()) << "made once per mix";
  EXPECT_EQ(calls, first_calls);
  EXPECT_EQ(refinement.update(all, key, colour_of, indices).made, second_half);
  EXPECT_EQ(indices, whole);
  const RefinementTotals totals = refinement.totals(all);
  EXPECT_EQ(totals.quads_flipped, flipped);
  EXPECT_EQ(totals.quads_subdivided, sub.replaced_quads.size());
  EXPECT_EQ(totals.subdivision_triangles, sub.triangles.size() / 3);

  // Each unit's run holds its own polygons' sub-quads; units not asked for have none.
  std::vector<ShadedVertex> triangles;
  std::vector<IndexRange> runs;
  refinement.gather(first_half, triangles, runs);
  ASSERT_EQ(runs.size(), f.layout.units());
  EXPECT_EQ(triangles.size(), 3 * std::size_t(refinement.totals(first_half).subdivision_triangles));
  for (const std::uint32_t u : second_half) EXPECT_EQ(runs[u].count, 0u) << u;
  for (const std::uint32_t u : first_half)
    for (std::uint32_t k = runs[u].first; k < runs[u].first + runs[u].count; ++k)
      ASSERT_EQ(f.layout.unit_of_polygon[triangles[k].polygon], u);

  // A new mix makes each unit again when it is next asked for.
  const RefinementKey dimmed{{1.0f, 0.2f}, kThreshold, kDepth};
  EXPECT_EQ(refinement.update(second_half, dimmed, colour_of, indices).made, second_half);
  EXPECT_EQ(refinement.totals(first_half).subdivision_triangles, 0u) << "the first half is not made for it";
  EXPECT_EQ(refinement.update(all, dimmed, colour_of, indices).made, first_half);
  refinement.forget();
  EXPECT_EQ(refinement.totals(all).quads_flipped, 0u);
  EXPECT_EQ(refinement.update(all, dimmed, colour_of, indices).made, all) << "forgotten: every unit again";
}

// Out of time after every unit: each call makes one more, in the order asked, until all are made; the result
// is the same as making them at once.
TEST(UnitRefinement, ATimeSliceMakesAtLeastOneUnitACallInOrder) {
  const Fixture f = rooms({1.0f, 0.7f});
  std::vector<std::uint32_t> order(f.layout.units());
  std::iota(order.rbegin(), order.rend(), 0u);  // last unit first
  const RefinementKey key{f.levels, 0.01f, 3};
  const auto colour_of = [&](std::uint32_t v) { return f.colour[v]; };
  UnitRefinement sliced(input_of(f)), at_once(input_of(f));
  std::vector<std::uint32_t> sliced_indices = f.layout.fine.indices, at_once_indices = f.layout.fine.indices;
  ASSERT_TRUE(at_once.update(order, key, colour_of, at_once_indices).finished);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const UnitRefinement::Update step =
        sliced.update(order, key, colour_of, sliced_indices, [] { return true; });
    ASSERT_EQ(step.made, std::vector<std::uint32_t>{order[k]}) << k;
    EXPECT_EQ(step.finished, k + 1 == order.size()) << k;
  }
  EXPECT_TRUE(sliced.update(order, key, colour_of, sliced_indices, [] { return true; }).finished);
  EXPECT_EQ(sliced_indices, at_once_indices);
  EXPECT_EQ(sliced.totals(order).subdivision_triangles, at_once.totals(order).subdivision_triangles);
}

// A slice's units appended after a gather of the units made before get the runs, counted on from where the
// gather ended, and the triangles a gather of every unit gives them; unmade() moves only when made units are
// unmade (a new mix, forget), so what was gathered under one value is still what the units hold.
TEST(UnitRefinement, AppendedUnitsMatchAWholeGather) {
  const Fixture f = rooms({1.0f, 0.7f});
  const RefinementKey key{f.levels, 0.01f, 3};
  const auto colour_of = [&](std::uint32_t v) { return f.colour[v]; };
  std::vector<std::uint32_t> sight(f.layout.units());
  std::iota(sight.begin(), sight.end(), 0u);
  UnitRefinement refinement(input_of(f));
  std::vector<std::uint32_t> indices = f.layout.fine.indices;
  ASSERT_EQ(refinement.update(sight, key, colour_of, indices, [] { return true; }).made.size(), 1u);
  const std::uint64_t unmade = refinement.unmade();
  std::vector<ShadedVertex> buffer;
  std::vector<IndexRange> runs;
  refinement.gather(sight, buffer, runs);
  const std::size_t gathered = buffer.size();
  while (true) {
    const UnitRefinement::Update step =
        refinement.update(sight, key, colour_of, indices, [] { return true; });
    std::vector<ShadedVertex> added;
    refinement.append(step.made, added, runs, std::uint32_t(buffer.size()));
    buffer.insert(buffer.end(), added.begin(), added.end());
    if (step.finished) break;
  }
  EXPECT_EQ(refinement.unmade(), unmade) << "making more unmakes nothing";
  std::vector<ShadedVertex> whole;
  std::vector<IndexRange> whole_runs;
  refinement.gather(sight, whole, whole_runs);
  ASSERT_EQ(buffer.size(), whole.size());
  ASSERT_GT(whole.size(), 0u);
  std::size_t appended = 0;
  for (const std::uint32_t u : sight) {
    ASSERT_EQ(runs[u].count, whole_runs[u].count) << u;
    appended += runs[u].count > 0 && runs[u].first >= gathered;
    for (std::uint32_t k = 0; k < runs[u].count; ++k) {
      EXPECT_EQ(buffer[runs[u].first + k].position, whole[whole_runs[u].first + k].position) << u;
      EXPECT_EQ(buffer[runs[u].first + k].radiosity, whole[whole_runs[u].first + k].radiosity) << u;
    }
  }
  EXPECT_GT(appended, 0u) << "units made after the first gather came after it";
  // Appending units that have runs, or are not made, adds nothing.
  std::vector<ShadedVertex> none;
  refinement.append(sight, none, runs, 0);
  EXPECT_TRUE(none.empty());

  const RefinementKey other{{0.5f, 0.7f}, 0.01f, 3};
  (void)refinement.update(std::vector<std::uint32_t>{}, other, colour_of, indices);
  EXPECT_GT(refinement.unmade(), unmade) << "a new mix unmakes the units";
  const std::uint64_t after_mix = refinement.unmade();
  refinement.forget();
  EXPECT_GT(refinement.unmade(), after_mix);
}

// What units outside the sight keep is bounded: past the bound the unit seen longest ago lets its quads and
// sub-quads go and is made again, to the same indices and sub-quads, when next seen; the sight's units keep
// theirs whatever the bound.
TEST(UnitRefinement, UnitsOutOfSightLetGoOldestFirstPastTheBound) {
  const Fixture f = rooms({1.0f, 0.7f});
  const RefinementKey key{f.levels, 0.01f, 3};
  const auto colour_of = [&](std::uint32_t v) { return f.colour[v]; };
  const std::size_t units = f.layout.units();
  // Each unit's bytes, made alone without a bound.
  std::vector<std::size_t> bytes(units);
  std::vector<std::uint32_t> with_sub_quads;
  UnitRefinement unbounded(input_of(f), std::numeric_limits<std::size_t>::max());
  std::vector<std::uint32_t> reference = f.layout.fine.indices;
  for (std::uint32_t u = 0; u < units; ++u) {
    const std::size_t before = unbounded.kept_bytes();
    (void)unbounded.update(std::vector<std::uint32_t>{u}, key, colour_of, reference);
    bytes[u] = unbounded.kept_bytes() - before;
    if (unbounded.totals(std::vector<std::uint32_t>{u}).subdivision_triangles > 0)
      with_sub_quads.push_back(u);
  }
  ASSERT_GE(with_sub_quads.size(), 3u);
  EXPECT_EQ(unbounded.kept_bytes(), std::accumulate(bytes.begin(), bytes.end(), std::size_t(0)))
      << "nothing let go without a bound";

  // A bound of 0: only the sight keeps anything.
  UnitRefinement none(input_of(f), 0);
  std::vector<std::uint32_t> indices = f.layout.fine.indices;
  for (std::uint32_t u = 0; u < units; ++u) {
    EXPECT_EQ(none.update(std::vector<std::uint32_t>{u}, key, colour_of, indices).made,
              std::vector<std::uint32_t>{u});
    EXPECT_EQ(none.kept_bytes(), bytes[u]) << u;
  }
  EXPECT_EQ(indices, reference) << "diagonals chosen stay in the indices when the quads are let go";
  const std::uint32_t back = with_sub_quads.front();
  EXPECT_EQ(none.update(std::vector<std::uint32_t>{back}, key, colour_of, indices).made,
            std::vector<std::uint32_t>{back})
      << "let go, so made again";
  std::vector<ShadedVertex> again, first;
  std::vector<IndexRange> runs;
  none.gather(std::vector<std::uint32_t>{back}, again, runs);
  unbounded.gather(std::vector<std::uint32_t>{back}, first, runs);
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(again[k].position, first[k].position) << k;
    EXPECT_EQ(again[k].radiosity, first[k].radiosity) << k;
  }
  EXPECT_EQ(indices, reference);

  // Oldest first: the largest unit seen, then two others no larger; a bound that holds the first two lets
  // the oldest go when the third comes and keeps the other two.
  std::vector<std::uint32_t> by_size = with_sub_quads;
  std::sort(by_size.begin(), by_size.end(),
            [&](std::uint32_t a, std::uint32_t b) { return bytes[a] > bytes[b]; });
  const std::uint32_t oldest = by_size[0], middle = by_size[1], newest = by_size.back();
  UnitRefinement bounded(input_of(f), bytes[oldest] + bytes[middle]);
  for (const std::uint32_t u : {oldest, middle, newest})
    (void)bounded.update(std::vector<std::uint32_t>{u}, key, colour_of, indices);
  EXPECT_EQ(bounded.kept_bytes(), bytes[middle] + bytes[newest]);
  EXPECT_EQ(bounded.totals(std::vector<std::uint32_t>{oldest}).subdivision_triangles, 0u) << "let go";
  EXPECT_GT(bounded.totals(std::vector<std::uint32_t>{middle}).subdivision_triangles, 0u) << "kept";
  EXPECT_TRUE(
      bounded.update(std::vector<std::uint32_t>{middle, newest}, key, colour_of, indices).made.empty());
}

}  // namespace unit_refinement_test
}  // namespace walk::render::test
