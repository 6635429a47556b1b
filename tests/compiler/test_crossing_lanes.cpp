// The AVX-512 listing kernel (crossing_lanes.hpp) against the scalar walk it replaces: the kernel alone on
// listings placed exactly on each bound of the accepted interval and of their in-plane bounds, and the whole
// walk on the shared models, where the lanes and the scalar merge must give bit-identical hits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "compiler/raycast/axial_caster.hpp"
#include "compiler/raycast/crossing_lanes.hpp"
#include "tools/bench_support/ray_models.hpp"
#include "tools/bench_support/ray_sets.hpp"

namespace walk::compiler {
namespace test_crossing_lanes {  // named, not anonymous: the suite compiles as unity batches

// The scalar walk's own test of one listing (plane_blocks.hpp), the reference for the kernel.
bool scalar_crosses(const CrossingLanes& l, std::uint32_t j, int k, const CrossingRay& r, double& t) {
  const int u = kPlaneU[k], v = kPlaneV[k];
  t = (l.coord[j] - r.o[k]) * r.inv[k];
  const double pu = r.o[u] + t * r.d[u], pv = r.o[v] + t * r.d[v];
  return t >= r.t_enter && t > r.tmin && t <= r.t_exit && t < r.limit && pu >= l.u0[j] && pu <= l.u1[j] &&
         pv >= l.v0[j] && pv <= l.v1[j];
}

TEST(CrossingLanes, KernelPicksExactlyTheScalarWalksListings) {
  if (!crossing_lanes_available()) GTEST_SKIP() << "this CPU has no AVX-512: the walk uses the scalar merge";
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int crossings = 0, on_bounds = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double o[3] = {unit(rng), unit(rng), unit(rng)};
    double d[3] = {unit(rng), unit(rng), unit(rng)};
    if (trial % 7 == 0) d[trial % 3] = 0.0;  // parallel to one axis' planes: the kernel skips them
    double inv[3];
    for (int k = 0; k < 3; ++k) inv[k] = d[k] == 0.0 ? 0.0 : 1.0 / d[k];
    // 0..21 listings per axis (up to kGatheredMax in all): every tail length of the 8-wide loop.
    const std::uint32_t per_axis[3] = {static_cast<std::uint32_t>(rng() % 22),
                                       static_cast<std::uint32_t>(rng() % 22),
                                       static_cast<std::uint32_t>(rng() % 22)};
    const std::uint32_t first = 3;  // listings of other blocks before this one's
    CrossingLanes lanes;
    for (std::uint32_t j = 0; j < first; ++j) lanes.push_back(0.0, -9.0, 9.0, -9.0, 9.0);
    std::uint32_t end[3];
    const double t_enter = 0.2 * unit(rng), t_exit = 1.0 + unit(rng), tmin = 0.1 * unit(rng);
    const double limit = trial % 3 == 0 ? INFINITY : 1.5 + unit(rng);
    for (int k = 0; k < 3; ++k) {
      const int u = kPlaneU[k], v = kPlaneV[k];
      for (std::uint32_t n = 0; n < per_axis[k]; ++n) {
        double c = 2.0 * unit(rng);
        const int kind = static_cast<int>(rng() % 6);
        // Planes exactly where the ray's t equals an end of the interval.
        if (d[k] != 0.0 && kind == 1) c = o[k] + t_enter * d[k];
        if (d[k] != 0.0 && kind == 2) c = o[k] + t_exit * d[k];
        if (d[k] != 0.0 && kind == 3) c = o[k] + tmin * d[k];
        const double t = (c - o[k]) * inv[k];
        const double pu = o[u] + t * d[u], pv = o[v] + t * d[v];
        double u0 = pu - std::abs(unit(rng)), u1 = pu + std::abs(unit(rng));
        double v0 = pv - std::abs(unit(rng)), v1 = pv + std::abs(unit(rng));
        if (kind == 4) u0 = pu;  // the crossing exactly on a bound
        if (kind == 5) v1 = pv;
        if (kind == 0 && n % 2 == 1) u0 = pu + 1e-3;  // just outside
        if (kind == 0 && n % 4 == 3) c = NAN;
        // Items distinct per listing, with a count in the high half, to check they come out with it.
        const auto index = static_cast<std::uint32_t>(lanes.coord.size());
        lanes.push_back(c, u0, u1, v0, v1, 1000 + 7 * index, index % 5 + 1);
      }
      end[k] = static_cast<std::uint32_t>(lanes.coord.size());
    }
    const CrossingRay ray{o, d, inv, t_enter, tmin, t_exit, limit};
    // Room for the whole vectors the kernel stores past its last crossing, and a guard after it.
    constexpr std::uint32_t kRoom = kGatheredMax + kCrossingSlack;
    double ct[kRoom + 1], cu[kRoom + 1], cv[kRoom + 1];
    std::uint32_t ci[kRoom + 1];
    std::uint64_t items[kRoom + 1];
    ct[kRoom] = cu[kRoom] = cv[kRoom] = -7.0;
    ci[kRoom] = 7;
    items[kRoom] = 7;
    const int n = gather_crossings(lanes, first, end, ray, {ct, cu, cv, ci, items});
    ASSERT_TRUE(ct[kRoom] == -7.0 && cu[kRoom] == -7.0 && cv[kRoom] == -7.0 && ci[kRoom] == 7 &&
                items[kRoom] == 7)
        << "trial " << trial << ": the kernel wrote past the room it was promised";
    int want = 0;
    std::uint32_t lo = first;
    for (int k = 0; k < 3; ++k) {
      for (std::uint32_t j = lo; j < end[k]; ++j) {
        double t = 0.0;
        if (d[k] == 0.0 || !scalar_crosses(lanes, j, k, ray, t)) continue;
        ASSERT_LT(want, n) << "trial " << trial << ": the kernel missed listing " << j;
        EXPECT_EQ(ci[want], j) << "trial " << trial;
        EXPECT_EQ(items[want], lanes.items[j]) << "trial " << trial;
        EXPECT_EQ(ct[want], t) << "trial " << trial;  // bit-identical: same IEEE operations
        EXPECT_EQ(cu[want], ray.o[kPlaneU[k]] + t * ray.d[kPlaneU[k]]);
        on_bounds += (t == t_enter || t == t_exit || lanes.u0[j] == cu[want] || lanes.v1[j] == cv[want]);
        ++want;
      }
      lo = end[k];
    }
    ASSERT_EQ(n, want) << "trial " << trial << ": the kernel kept a listing the scalar test rejects";
    crossings += n;
  }
  EXPECT_GT(crossings, 10000);
  EXPECT_GT(on_bounds, 1000) << "too few crossings exactly on a bound to test the inclusive ends";
  std::printf("kernel: %d crossings, %d exactly on a bound\n", crossings, on_bounds);
}

// Same hits, bit for bit, from the lanes and from the scalar merge, on every axial shared model.
class LanesOnModels : public ::testing::TestWithParam<const char*> {};

TEST_P(LanesOnModels, SameHitsAsTheScalarMerge) {
  const auto model = bench::load_ray_model(GetParam(), WALK_SHARED_DATA);
  const AxialCaster lanes(model.triangles, BlockSizing{});
  const AxialCaster scalar(model.triangles, BlockSizing{.lanes = false});
  ASSERT_FALSE(scalar.planes().blocks().uses_lanes());
  if (!lanes.planes().blocks().uses_lanes()) GTEST_SKIP() << "this CPU has no AVX-512";
  std::size_t rays = 0, hits = 0, occluded = 0;
  for (auto&& set :
       {bench::primary_rays(model.triangles, 50000, 21), bench::radiosity_rays(model.triangles, 50000, 22),
        bench::occlusion_rays(model.triangles, 50000, 23), bench::random_rays(model.triangles, 50000, 24)})
    for (const Ray& r : set) {
      const RayHit a = lanes.closest(r), b = scalar.closest(r);
      ASSERT_EQ(a.hit(), b.hit()) << GetParam() << " ray " << rays;
      if (a.hit()) {
        ASSERT_EQ(a.t, b.t) << GetParam() << " ray " << rays;
        ASSERT_EQ(a.triangle, b.triangle) << GetParam() << " ray " << rays;
        ASSERT_EQ(a.front, b.front) << GetParam() << " ray " << rays;
      }
      const bool oa = lanes.occluded(r);
      ASSERT_EQ(oa, scalar.occluded(r)) << GetParam() << " ray " << rays;
      ++rays;
      hits += a.hit();
      occluded += oa;
    }
  EXPECT_GT(hits, rays / 2);
  std::printf("%s: %zu rays, %zu hits, %zu occluded, identical (%zu blocks of %u-%u listings gathered)\n",
              GetParam(), rays, hits, occluded, lanes.planes().blocks().stats().gathered_big, kGathered + 1,
              kGatheredMax);
}

// The lanes take blocks of more than kGathered listings only where rays usually cross blocks rather than end
// in them: the Quake levels' small blocks (so the test above compares those blocks with the merge), not the
// office's single block of 18 listings, ten times its mean free path.
TEST(LanesOnModels, BigBlocksGatheredOnlyWhereRaysCrossThem) {
  if (!crossing_lanes_available()) GTEST_SKIP() << "this CPU has no AVX-512: the walk uses the scalar merge";
  const auto stats = [](const char* name) {
    const auto model = bench::load_ray_model(name, WALK_SHARED_DATA);
    return AxialCaster(model.triangles).planes().blocks().stats();
  };
  const auto e1m1 = stats("e1m1"), dm1 = stats("dm1"), office = stats("office");
  EXPECT_GT(e1m1.gathered_big, 0u);
  EXPECT_GT(dm1.gathered_big, 0u);
  EXPECT_GT(e1m1.mean_free_path, 10.0);
  EXPECT_EQ(office.gathered_big, 0u);
  EXPECT_EQ(office.blocks[0] * office.blocks[1] * office.blocks[2], 1u);
  EXPECT_GT(office.entries, kGathered) << "the office's block is no longer one the rule has to decide";
  EXPECT_LT(office.mean_free_path, 5.0);
}

INSTANTIATE_TEST_SUITE_P(Shared, LanesOnModels, ::testing::Values("house", "office", "e1m1", "dm1"));

}  // namespace test_crossing_lanes
}  // namespace walk::compiler
