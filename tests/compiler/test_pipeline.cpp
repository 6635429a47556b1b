// The whole display compiler on the real EnergyPlus house: what the bundle holds is computed, not faked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "compiler/pipeline.hpp"
#include "compiler/radiosity/compact_light.hpp"
#include "compiler/visibility/draw_order.hpp"
#include "model/compact_code.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_pipeline {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

const std::string kHouseScene = std::string(WALK_SOURCE_DIR) + "/config/scenes/house.toml";

class PipelineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_pipeline_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A scene config in the temp folder whose model is `model_path`, with the house's rules.
  std::string scene_for(const std::string& model_path, const std::string& extra = {}) {
    std::ifstream in(kHouseScene);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const auto start = text.find("file = ");
    text.replace(start, text.find('\n', start) - start, "file = \"" + model_path + "\"");
    const std::string path = (dir_ / "scene.toml").string();
    std::ofstream(path) << text << extra;
    return path;
  }
  fs::path dir_;
};

TEST_F(PipelineTest, HouseCompilesWithOneLitCircuitPerRoom) {
  const CompileResult r = compile_scene(load_scene_config(kHouseScene));
  const auto& b = r.bundle;
  // 16 zones + the arrow layer "1" + "Building Shading"; each zone gets one ceiling panel and its own
  // circuit.
  EXPECT_EQ(b.groups.size(), 18u);
  EXPECT_EQ(b.luminaires.size(), 16u);
  EXPECT_EQ(b.circuits.size(), 16u);
  ASSERT_EQ(b.light.rows(), b.vertices.size());
  for (const auto& e : b.light.entries) {
    ASSERT_LT(e.circuit, b.circuits.size());
    for (float v : e.rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  }
  // Sparse: a vertex holds only the circuits whose light reaches it, not all 16 (the final gather's rays
  // meet patches lit through doors and the stair by about ten of them).
  EXPECT_LT(b.light.entries.size(), b.vertices.size() * b.circuits.size() * 3 / 4);
  for (const auto& p : b.polygons) EXPECT_NE(p.role, static_cast<std::uint32_t>(model::Role::Opening));
  // The coarse form drawn while moving: one range per polygon, over its own vertices, far fewer triangles.
  ASSERT_EQ(b.coarse_ranges.size(), b.polygons.size());
  for (std::size_t i = 0; i < b.polygons.size(); ++i) {
    const auto& range = b.coarse_ranges[i];
    const auto& p = b.polygons[i];
    ASSERT_GT(range.index_count, 0u) << i;
    EXPECT_LE(range.index_count, p.index_count) << i;
    for (std::uint32_t k = range.first_index; k < range.first_index + range.index_count; ++k)
      ASSERT_TRUE(b.coarse_indices[k] >= p.first_vertex &&
                  b.coarse_indices[k] < p.first_vertex + p.vertex_count);
  }
  EXPECT_LT(b.coarse_indices.size() * 10, b.indices.size());
  // INDX is laid out for the cells: far fewer multi-draw ranges than with polygons in id order. (Leaving
  // back faces out of each cell's PVS scatters the sets: 179 ranges before, 256 after, against 629-768;
  // with detail left out of the partition's counts the cells change: 275 against 498.)
  model::BundleContents id_order = b;
  std::uint32_t next = 0;
  for (auto& p : id_order.polygons) {
    p.first_index = next;
    next += p.index_count;
  }
  EXPECT_LT(3 * count_draw_ranges(b), 2 * count_draw_ranges(id_order));
  EXPECT_LT(count_draw_ranges(b), 16 * b.cells.size());

  // Over each room's floor (EnergyPlus splits non-convex floors into triangles), the room's own circuit gives
  // more light than any other circuit.
  const std::size_t circuits = b.circuits.size();
  std::map<std::string, std::uint32_t> circuit_of;
  for (std::uint32_t c = 0; c < circuits; ++c) circuit_of[b.strings.c_str() + b.circuits[c].name] = c;
  std::map<std::string, std::vector<double>> floor_light;
  for (const auto& poly : b.polygons) {
    const auto& v0 = b.vertices[poly.first_vertex];
    if (poly.role != 0 || v0.normal[2] < 0.99f) continue;  // floors only
    auto& sum = floor_light[b.strings.c_str() + b.groups[poly.group].name];
    sum.resize(circuits, 0.0);
    for (std::uint32_t v = poly.first_vertex; v < poly.first_vertex + poly.vertex_count; ++v)
      for (const auto& e : b.light.row(v)) sum[e.circuit] += e.rgb[1];
  }
  std::size_t rooms_checked = 0;
  for (const auto& [room, sum] : floor_light) {
    const std::uint32_t own = circuit_of.at(room);
    EXPECT_GT(sum[own], 0.0) << room;
    for (std::size_t c = 0; c < circuits; ++c) {
      if (c != own) {
        EXPECT_GT(sum[own], sum[c]) << room << " vs circuit " << b.strings.c_str() + b.circuits[c].name;
      }
    }
    ++rooms_checked;
  }
  EXPECT_GE(rooms_checked, 16u);

  // Doors were cut: the stage ran and used every door and passage of the house (17 doors + 7 holes).
  bool openings_ran = false;
  for (const auto& s : r.stages)
    if (s.name == "openings") openings_ran = s.ran;
  EXPECT_TRUE(openings_ran);
}

TEST_F(PipelineTest, SecondCompileIsSkippedWhenNothingChanged) {
  const std::string out = (dir_ / "house.walk").string();
  EXPECT_TRUE(compile_to_file(kHouseScene, out, false));
  EXPECT_FALSE(compile_to_file(kHouseScene, out, false));
  EXPECT_TRUE(compile_to_file(kHouseScene, out, true));
  const auto bundle = model::Bundle::open(out);
  EXPECT_EQ(bundle->meta().scene_hash, scene_hash(load_scene_config(kHouseScene)));
}

TEST_F(PipelineTest, LightIsReusedUnlessItsInputsChange) {
  const std::string model = std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf";
  const std::string out = (dir_ / "house.walk").string();
  auto stage = [](const std::vector<StageReport>& stages, const std::string& name) {
    for (const auto& s : stages)
      if (s.name == name) return s;
    return StageReport{};
  };
  std::vector<StageReport> stages;
  ASSERT_TRUE(compile_to_file(scene_for(model), out, false, &stages));
  EXPECT_TRUE(stage(stages, "light").ran);
  const auto first = model::Bundle::open(out);
  const std::vector<float> light = first->light().dense(first->circuits().size());

  // Display-only knobs changed: the solve is kept, byte for byte.
  std::ifstream in(dir_ / "scene.toml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("ambient = "), text.find('\n', text.find("ambient = ")) - text.find("ambient = "),
               "ambient = 0.5");
  std::ofstream(dir_ / "scene.toml") << text;
  ASSERT_TRUE(compile_to_file((dir_ / "scene.toml").string(), out, false, &stages));
  EXPECT_FALSE(stage(stages, "light").ran);
  EXPECT_TRUE(stage(stages, "light").reused);
  const auto second = model::Bundle::open(out);
  EXPECT_EQ(light, second->light().dense(second->circuits().size()));
  EXPECT_FLOAT_EQ(second->meta().ambient, 0.5f);

  // A reflectance changed: the light must be solved again.
  text.replace(text.find("reflectance = [0.72"), 19, "reflectance = [0.70");
  std::ofstream(dir_ / "scene.toml") << text;
  ASSERT_TRUE(compile_to_file((dir_ / "scene.toml").string(), out, false, &stages));
  EXPECT_TRUE(stage(stages, "light").ran);
}

TEST_F(PipelineTest, CompactLightIsStoredWithItsMeasuredError) {
  const CompileResult r = compile_scene(load_scene_config(kHouseScene));
  const auto& b = r.bundle;
  ASSERT_EQ(b.compact_colour.size(), b.vertices.size());
  ASSERT_EQ(b.compact_intensity.rows(), b.vertices.size());
  ASSERT_EQ(b.polygon_light.rows(), b.polygons.size());
  // Each circuit is shown compact where its own error is within the limit, else full; the record says
  // which and carries the error that decided it.
  std::vector<std::uint8_t> glowing(b.vertices.size(), 0);  // the panels, left out of the errors
  for (const auto& p : b.polygons)
    if (p.role == std::uint32_t(model::Role::Luminaire))
      std::fill_n(glowing.begin() + p.first_vertex, p.vertex_count, std::uint8_t(1));
  const CompactLight c = choose_light_forms(b.light.view(), b.vertices.size(), b.circuits.size(), glowing);
  // Measured over the panels too, the error would be a fraction of it: their exitance swamps the walls'
  // (the more so the fewer vertices the walls have: 0.56 of it at the house's refined 0.2 m dicing).
  const CompactLight with_panels = choose_light_forms(b.light.view(), b.vertices.size(), b.circuits.size());
  EXPECT_LT(with_panels.rms_error_all_on, 0.7 * c.rms_error_all_on);
  EXPECT_LT(c.rms_error_all_on, 0.05);
  EXPECT_GT(c.rms_error_all_on, 0.0);  // lossy: a zero would mean the error is not measured
  std::size_t compact = 0;
  for (std::size_t i = 0; i < b.circuits.size(); ++i) {
    EXPECT_FLOAT_EQ(b.circuits[i].compact_scale, c.scale[i]);
    EXPECT_FLOAT_EQ(b.circuits[i].compact_error, float(c.circuit_rms[i]));
    const bool shown_compact = b.circuits[i].light_form == model::LightForm::Compact;
    EXPECT_EQ(shown_compact, c.circuit_rms[i] <= kCompactErrorLimit) << i;
    compact += shown_compact;
  }
  EXPECT_GT(compact, 0u);  // the house's circuits are white lamps: most are within the limit
  // And they reach the file the runtime maps.
  const std::string path = (dir_ / "compact.walk").string();
  model::write_bundle(path, b);
  const auto read = model::Bundle::open(path);
  EXPECT_EQ(read->compact_colour().size(), b.vertices.size());
  EXPECT_EQ(read->compact_intensity().codes.size(), b.compact_intensity.codes.size());
  EXPECT_EQ(read->polygon_light().entries.size(), b.polygon_light.entries.size());
  EXPECT_EQ(read->light().rows(), b.vertices.size());
}

TEST(CompactLight, GreyLightOfOneCircuitRoundTripsWithinQuantisation) {
  // From 50 W/m2 down to a millionth of it: the hot spot and the dim wall alike.
  std::vector<float> light;
  for (int v = 0; v < 1000; ++v) light.insert(light.end(), 3, 50.0f * std::pow(1e-6f, float(v) / 999.0f));
  const auto rows = model::LightRows::from_dense(light, 1);
  const CompactLight c = compact_light(rows.view(), 1000, 1);
  const auto back = expand_compact(c, rows.view(), 1000, 1);
  // Logarithmic coding: half a step is a ratio of 2^(8/254) (2.2 %) at every level down to 2^-16 of the
  // scale; below that a value reads 0 or the smallest code's.
  const double half_step = std::exp2(0.5 * model::kCompactStops / 254.0) - 1.0;
  const double floor = 50.0 * std::exp2(-model::kCompactStops);
  for (std::size_t i = 0; i < light.size(); ++i) {
    if (light[i] >= floor)
      EXPECT_NEAR(back[i], light[i], light[i] * half_step * 1.01 + 1e-6) << i;
    else
      EXPECT_LE(back[i], floor * 1.01) << i;
  }
}

TEST(CompactLight, CodesAreMonotoneAndRoundTrip) {
  EXPECT_EQ(model::compact_code(0.0), 0);
  EXPECT_EQ(model::compact_code(-1.0), 0);
  EXPECT_EQ(model::compact_code(std::nan("")), 0);
  EXPECT_EQ(model::compact_code(1.0), 255);
  EXPECT_EQ(model::compact_code(2.0), 255);  // above the scale: clamped
  EXPECT_EQ(model::compact_intensity(0), 0.0);
  EXPECT_DOUBLE_EQ(model::compact_intensity(255), 1.0);
  for (int k = 1; k < 256; ++k) {
    EXPECT_EQ(model::compact_code(model::compact_intensity(std::uint8_t(k))), k);
    if (k > 1) {
      EXPECT_GT(model::compact_intensity(std::uint8_t(k)), model::compact_intensity(std::uint8_t(k - 1)));
    }
  }
  // Far below code 1: nearer 0 than it.
  EXPECT_EQ(model::compact_code(0.4 * model::compact_intensity(1)), 0);
  EXPECT_EQ(model::compact_code(0.6 * model::compact_intensity(1)), 1);
}

// Two circuits over 500 vertices: a white one brightening along the row, and a red one that peaks where the
// white one is dim. One colour per vertex cannot hold both tints.
std::vector<float> white_and_red(std::size_t vertices) {
  std::vector<float> light;
  for (std::size_t v = 0; v < vertices; ++v) {
    const float t = float(v) / float(vertices - 1);
    light.insert(light.end(), {10.0f * t + 1.0f, 10.0f * t + 1.0f, 10.0f * t + 1.0f});  // circuit 0
    light.insert(light.end(), {8.0f * (1.0f - t) + 0.5f, 0.2f, 0.2f});                  // circuit 1
  }
  return light;
}

TEST(CompactLight, ATintedCircuitIsShownFullAndTheOthersCompact) {
  const std::size_t n = 500;
  const auto light = white_and_red(n);
  const auto rows = model::LightRows::from_dense(light, 2);
  const CompactLight both = compact_light(rows.view(), n, 2);
  EXPECT_GT(both.circuit_rms[1], kCompactErrorLimit);  // the shared colour misrepresents the red circuit
  const CompactLight chosen = choose_light_forms(rows.view(), n, 2);
  EXPECT_EQ(chosen.compact[0], 1);
  EXPECT_EQ(chosen.compact[1], 0);
  EXPECT_GT(chosen.circuit_rms[1], kCompactErrorLimit);  // the reason it is full, kept for the report
  EXPECT_LE(chosen.circuit_rms[0], kCompactErrorLimit);
  EXPECT_LT(chosen.circuit_rms[0], both.circuit_rms[0]);  // the colour now follows the white circuit only
  EXPECT_EQ(chosen.worst_circuit_rms, chosen.circuit_rms[0]);
  EXPECT_EQ(chosen.scale[1], 0.0f);
  // Shown: the full circuit exactly as solved, the compact one within its error.
  const auto shown = expand_compact(chosen, rows.view(), n, 2);
  for (std::size_t v = 0; v < n; ++v)
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(shown[(v * 2 + 1) * 3 + ch], light[(v * 2 + 1) * 3 + ch]);
  EXPECT_LT(chosen.rms_error_all_on, both.rms_error_all_on);
}

TEST(CompactLight, DarkAndUniformCircuitsStayCompact) {
  const std::size_t n = 64;
  std::vector<float> light;
  for (std::size_t v = 0; v < n; ++v) {
    light.insert(light.end(), {0.0f, 0.0f, 0.0f});                          // a circuit with no light here
    light.insert(light.end(), {float(v + 1), float(v + 1), float(v + 1)});  // grey
  }
  const CompactLight c = choose_light_forms(model::LightRows::from_dense(light, 2).view(), n, 2);
  EXPECT_EQ(c.compact[0], 1);
  EXPECT_EQ(c.compact[1], 1);
  EXPECT_EQ(c.circuit_rms[0], 0.0);
  EXPECT_LT(c.circuit_rms[1], 0.02);  // quantisation only: 4.5 % steps, RMS about step / sqrt(12)
  EXPECT_GT(c.circuit_rms[1], 0.0);
}

TEST_F(PipelineTest, BrokenModelLeavesNoBundle) {
  // The house cut off mid-entity.
  std::ifstream in(std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string broken = (dir_ / "broken.dxf").string();
  std::ofstream(broken) << text.substr(0, text.size() / 2);
  const std::string out = (dir_ / "broken.walk").string();
  try {
    compile_to_file(scene_for(broken), out, true);
    FAIL() << "a truncated DXF compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.dxf"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".walk"), std::string::npos) << e.path();
}

TEST_F(PipelineTest, ModelWithNothingToDrawIsAnError) {
  const std::string scene = scene_for(std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf", "\n");
  // Prepend a rule that ignores every face.
  std::ifstream in(scene);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("[[rules]]"), 0, "[[rules]]\nlayer = \".*\"\nrole = \"ignored\"\n\n");
  std::ofstream(scene) << text;
  try {
    compile_to_file(scene, (dir_ / "empty.walk").string(), true);
    FAIL() << "an empty model compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty model"), std::string::npos) << e.what();
  }
}

}  // namespace test_pipeline
}  // namespace walk::compiler
