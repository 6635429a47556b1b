// Every shared model through the cells stage and the visibility judge at a small size: the conservative
// PVS must miss no pixel. CI-sized: coarse lighting, one viewpoint per cell, small cube faces.
// The full-size figures come from `walk verify visibility` (docs/VISIBILITY.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "compiler/pipeline.hpp"
#include "compiler/scene/scene_config.hpp"
#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/verify_visibility.hpp"

namespace walk::compiler {
namespace test_visibility_shared {  // named, not anonymous: the suite compiles as unity batches

class VisibilityShared : public ::testing::TestWithParam<const char*> {};

// Both conservative methods, the default (combined: per-polygon flow united with samples) and the cell-level
// one, miss no pixel.
TEST_P(VisibilityShared, ConservativePvsMissesNoPixel) {
  const std::string scene = std::string(WALK_SOURCE_DIR) + "/config/scenes/" + GetParam() + ".toml";
  SceneConfig config;
  try {
    config = load_scene_config(scene);
  } catch (const std::exception& e) {
    GTEST_SKIP() << e.what();
  }
  if (!std::filesystem::exists(config.model_file)) GTEST_SKIP() << "no shared data: " << config.model_file;
  ASSERT_EQ(config.visibility.method, PvsMethod::Combined) << "the default";
  config.lighting.method = LightingMethod::Direct;
  config.lighting.samples_per_luminaire = 1;
  config.lighting.grid = 4.0;
  config.visibility.sample_points = 4;
  config.visibility.rays_per_point = 64;
  for (const PvsMethod method : {PvsMethod::Combined, PvsMethod::Conservative}) {
    config.visibility.method = method;
    const CompileResult r = compile_scene(config);
    const auto& b = r.bundle;
    ASSERT_FALSE(b.cells.empty());
    ASSERT_EQ(b.nodes.empty(), b.cells.size() == 1);
    // The portals the renderer walks: each on the face its two cells share, open at least one way.
    if (b.cells.size() > 1) {
      EXPECT_FALSE(b.portals.empty());
    }
    for (const auto& p : b.portals) {
      const int axis = int(p.flags & model::kPortalAxisMask);
      ASSERT_LT(axis, 3);
      EXPECT_NE(p.flags & (model::kPortalForward | model::kPortalBackward), 0u);
      EXPECT_NEAR(p.bounds_min[axis], b.cells[p.back].bounds_max[axis], 1e-3);
      EXPECT_NEAR(p.bounds_max[axis], b.cells[p.front].bounds_min[axis], 1e-3);
      for (int k = 0; k < 3; ++k) {
        if (k == axis) continue;
        EXPECT_GE(p.bounds_min[k],
                  std::max(b.cells[p.back].bounds_min[k], b.cells[p.front].bounds_min[k]) - 1e-3);
        EXPECT_LE(p.bounds_max[k],
                  std::min(b.cells[p.back].bounds_max[k], b.cells[p.front].bounds_max[k]) + 1e-3);
      }
    }

    VerifyOptions o;
    o.viewpoints = 1;
    o.resolution = 32;
    o.dense = 1;
    o.dense_resolution = 16;
    const VisibilityJudge judge(b.vertices, b.indices, b.polygons, o, b.void_facing);
    // Viewpoints beside every portal too: the widest views out of a cell, the hardest for its PVS.
    const BundleCells cells = bundle_cells(judge.polygons(), b.cells, o.cull_back_faces);
    std::size_t portal_eyes = 0;
    std::vector<std::uint64_t> cell_missed, cell_pixels;
    std::vector<bool> no_open_space;
    for (std::uint32_t c = 0; c < b.cells.size(); ++c) {
      if (b.cells[c].flags & model::kCellOutside) continue;  // off the walk: everything is drawn there
      const Box& box = cells.partition.cells[c];
      const CellViews v = judge.views(box, c, portal_viewpoints(cells.graph, box, c));
      portal_eyes += v.portal_viewpoints;
      const auto& rec = b.cells[c];
      const std::vector<std::uint32_t> pvs = model::cell_polygons(rec, b.pvs, b.clusters, b.cluster_polygons);
      cell_missed.push_back(judge.missed(v, pvs));
      cell_pixels.push_back(v.offsets.size() - 1);
      no_open_space.push_back(v.no_free_space);
    }
    // As `walk verify`: cells inside walls, in a model with open space elsewhere, are not judged.
    const std::vector<bool> judged = cells_to_judge(no_open_space);
    std::uint64_t missed = 0, pixels = 0;
    for (std::size_t i = 0; i < judged.size(); ++i) {
      if (!judged[i]) continue;
      missed += cell_missed[i];
      pixels += cell_pixels[i];
    }
    EXPECT_GT(pixels, 0u);
    if (b.cells.size() > 1) {
      EXPECT_GT(portal_eyes, 0u) << "cells with portals were looked at beside them";
    }
    std::printf("%s (%s): %zu cells, missed %llu of %llu pixels\n", GetParam(), pvs_method_name(method),
                b.cells.size(), static_cast<unsigned long long>(missed),
                static_cast<unsigned long long>(pixels));
    // DM1 missed 0.2% here until the portal planes of the flow were built with a stray +z component.
    EXPECT_EQ(missed, 0u) << GetParam() << " (" << pvs_method_name(method) << "): " << b.cells.size()
                          << " cells";
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, VisibilityShared,
                         ::testing::Values("house", "medium-office", "apartment-plan", "quake-e1m1",
                                           "quake-dm1", "conference-room", "cornell-box-obj", "sibenik"));

}  // namespace test_visibility_shared
}  // namespace walk::compiler
