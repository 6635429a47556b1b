// Leak test: rays from inside closed boxes of quads and of triangles, aimed exactly at vertices and at points
// on edges, must all hit the box (closest and any-hit), at the point they were aimed at. The axial boxes
// exercise the plane structure, the rotated ones the BSP and the watertight triangle test, the moved ones
// precision.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "compiler/raycast/axial_caster.hpp"
#include "tools/bench_support/leak_box.hpp"

namespace walk::compiler {
namespace test_ray_leak {  // named, not anonymous: the suite compiles as unity batches

// 10M rays in all through the axial boxes (5M quads, 5M triangles: about 4 s at -O2 on two threads); the
// rotated and moved boxes go through the BSP at about 0.5 Mrays/s, so they get 500k each here and 10M each
// in `walk bench rays --leak 10000000`.
constexpr std::size_t kAxialRays = 5000000;
constexpr std::size_t kOtherRays = 500000;

glm::dmat3 tilted() {
  return glm::dmat3(
      glm::rotate(glm::rotate(glm::dmat4(1.0), 0.37, glm::dvec3(0, 0, 1)), 0.61, glm::dvec3(1, 1, 0)));
}

struct LeakCase {
  const char* name;
  bool quads;
  bool rotated;
  double shift;
  bool scalar = false;  // the scalar merge instead of the AVX-512 lanes (where the CPU has them)
};

class RayLeak : public ::testing::TestWithParam<LeakCase> {};

TEST_P(RayLeak, NoRayEscapes) {
  const LeakCase c = GetParam();
  const auto box = bench::leak_box(c.quads, 5, c.rotated ? tilted() : glm::dmat3(1.0), model::Vec3(c.shift));
  const std::unique_ptr<RayCaster> caster =
      c.scalar ? std::make_unique<AxialCaster>(box.triangles, BlockSizing{.lanes = false})
               : make_ray_caster("axial", box.triangles);
  const auto start = std::chrono::steady_clock::now();
  std::size_t escapes = 0, any_escapes = 0, early = 0, total = 0;
  for (unsigned part = 0; part < 4; ++part) {
    const std::size_t count = (c.rotated || c.shift != 0.0 || c.scalar ? kOtherRays : kAxialRays) / 4;
    const auto rays = bench::leak_rays(box, count, 100 + part);
    std::vector<RayHit> hits(rays.size());
    std::vector<std::uint8_t> occluded(rays.size());
    caster->closest_batch(rays, hits, 2);
    caster->occluded_batch(rays, occluded, 2);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      if (!hits[i].hit())
        ++escapes;
      else if (std::abs(hits[i].t - 1.0) > 1e-6)
        ++early;  // the box is convex: the aimed-at point is first
      if (!occluded[i]) ++any_escapes;
    }
    total += rays.size();
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %zu triangles, %zu rays, escapes %zu (any-hit %zu), hits off target %zu, %.2f s\n", c.name,
              box.triangles.size(), total, escapes, any_escapes, early, s);
  EXPECT_EQ(escapes, 0u);
  EXPECT_EQ(any_escapes, 0u);
  EXPECT_EQ(early, 0u);
}

INSTANTIATE_TEST_SUITE_P(Boxes, RayLeak,
                         ::testing::Values(LeakCase{"axial_quads", true, false, 0.0},
                                           LeakCase{"axial_triangles", false, false, 0.0},
                                           LeakCase{"rotated_quads", true, true, 0.0},
                                           LeakCase{"rotated_triangles", false, true, 0.0},
                                           LeakCase{"far_axial_triangles", false, false, 1e6},
                                           LeakCase{"far_rotated_triangles", false, true, 1e6},
                                           LeakCase{"axial_triangles_scalar_merge", false, false, 0.0, true},
                                           LeakCase{"far_axial_quads_scalar_merge", true, false, 1e6, true}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace test_ray_leak
}  // namespace walk::compiler
