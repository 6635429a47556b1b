// walk probe's meter: a compiled CIE 171:2006 case 5.8 cube (a 10,000 lm isotropic fixture at the centre of
// a 4 m cube of reflectance 0.5) read at points over every face averages to the closed form
// E = flux / (S (1 - rho)); a meter inside a wall says so; a look ray reads luminance B / pi.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "compiler/lighting/path_reference.hpp"
#include "compiler/lighting/probe.hpp"
#include "compiler/lighting/stored_light.hpp"
#include "compiler/pipeline.hpp"
#include "model/bundle.hpp"
#include "model/luminaire_shapes.hpp"

namespace walk::compiler {
namespace test_probe {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;
constexpr double kFlux = 10000.0, kSide = 4.0, kRho = 0.5;

class ProbeTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("walk_probe_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // The cube, faces turned inwards.
    std::ofstream(dir_ / "cube.obj")
        << "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 4\nv 4 0 4\nv 4 4 4\nv 0 4 4\n"
           "f 1 2 3 4\nf 5 8 7 6\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\n";
    // An isotropic table; its flux is rescaled to 10,000 lm by the scene.
    std::ofstream(dir_ / "iso.ies")
        << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n"
           "100 100 100\n";
    std::ofstream(dir_ / "cube.toml") << "[model]\nfile = \"cube.obj\"\nup = \"z\"\n"
                                         "[[rules]]\nlayer = \".*\"\nmaterial = \"grey\"\n"
                                         "[materials.grey]\nreflectance = [0.5, 0.5, 0.5]\n"
                                         "[[luminaires.fixture]]\nname = \"centre\"\nposition = [2, 2, 2]\n"
                                         "photometry = \"iso.ies\"\nflux = 10000\n"
                                         "[lighting]\ngrid = 0.5\ntarget_error = 0.03\nresidual = 0.001\n";
    ASSERT_TRUE(
        compile_to_file((dir_ / "cube.toml").string(), (dir_ / "cube.walk").string(), true, &stages_));
    bundle_ = model::Bundle::open((dir_ / "cube.walk").string()).release();
  }
  static void TearDownTestSuite() {
    delete bundle_;
    fs::remove_all(dir_);
  }
  static inline fs::path dir_;
  static inline std::vector<StageReport> stages_;
  static inline model::Bundle* bundle_ = nullptr;
};

TEST_F(ProbeTest, TheLightStageMeetsItsTargetError) {
  const auto light =
      std::find_if(stages_.begin(), stages_.end(), [](const auto& s) { return s.name == "light"; });
  ASSERT_NE(light, stages_.end());
  ASSERT_TRUE(light->estimated_error) << light->detail;
  const double estimate = *light->estimated_error;
  EXPECT_LE(estimate, 0.03 * 1.15) << light->detail;  // within the stage's slack of the target
  EXPECT_GT(estimate, 0.03 * 0.5) << light->detail;   // and not far more rays than it asked for
  EXPECT_NE(light->detail.find("target 3.00%: pilot"), std::string::npos) << light->detail;
}

TEST_F(ProbeTest, TheFixtureKeepsItsShapeInTheBundle) {
  const auto luminaires = model::load_luminaires(*bundle_);
  ASSERT_EQ(luminaires.size(), 1u);
  EXPECT_EQ(luminaires[0].kind, model::LuminaireKind::Photometric);
  ASSERT_TRUE(luminaires[0].distribution);
  EXPECT_NEAR(luminaires[0].distribution->candela_at(33, 77), 100.0, 1e-4);
  EXPECT_NEAR(luminaires[0].power.g * 179.0, kFlux, 1e-3 * kFlux);
}

TEST_F(ProbeTest, MeanIlluminanceOverTheCubeMatchesCie171) {
  // Meters at the middles of an 8 x 8 grid on each face, 1 mm off it, facing in.
  constexpr int kGrid = 8;
  struct Face {
    int axis;
    double at;
    double facing;
  };
  const Face faces[] = {{0, 0, 1}, {0, kSide, -1}, {1, 0, 1}, {1, kSide, -1}, {2, 0, 1}, {2, kSide, -1}};
  double sum_total = 0.0, sum_direct = 0.0;
  int count = 0;
  const Probe meter(*bundle_);
  ProbeOptions o;
  o.indirect_rays = 1024;
  for (const auto& f : faces) {
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        const int u = (f.axis + 1) % 3, v = (f.axis + 2) % 3;
        o.at = model::Vec3(0.0);
        o.at[f.axis] = f.at + 1e-3 * f.facing;
        o.at[u] = (i + 0.5) * kSide / kGrid;
        o.at[v] = (j + 0.5) * kSide / kGrid;
        o.normal = model::Vec3(0.0);
        o.normal[f.axis] = f.facing;
        const auto r = meter.read(o);
        ASSERT_EQ(r.circuits.size(), 1u);
        EXPECT_LT(r.back_face_fraction, 1e-3);
        sum_direct += r.circuits[0].direct_lux;
        sum_total += r.circuits[0].direct_lux + r.circuits[0].indirect_lux;
        ++count;
      }
    }
  }
  constexpr double kArea = 6.0 * kSide * kSide;
  const double direct = sum_direct / count, total = sum_total / count;
  std::printf(
      "probe over the CIE 171 cube: direct %.2f lx (flux / S %.2f), total %.2f lx (closed form %.2f)\n",
      direct, kFlux / kArea, total, kFlux / (kArea * (1.0 - kRho)));
  // The 8 x 8 midpoint rule over each face's smooth direct light is good to about 0.5 %.
  EXPECT_NEAR(direct, kFlux / kArea, 0.01 * kFlux / kArea);
  EXPECT_NEAR(total, kFlux / (kArea * (1.0 - kRho)), 0.02 * kFlux / (kArea * (1.0 - kRho)));
}

TEST_F(ProbeTest, AMeterBehindAWallSaysSoAndALookReadsLuminance) {
  const Probe meter(*bundle_);
  ProbeOptions o;
  o.at = {2, 2, -0.5};  // under the floor, facing up into its back
  o.indirect_rays = 256;
  const auto under = meter.read(o);
  EXPECT_GT(under.back_face_fraction, 0.9);      // the rest pass beside the floor, nearly level
  EXPECT_EQ(under.circuits[0].direct_lux, 0.0);  // the floor shadows the fixture
  o.at = {2, 2, 2.5};
  o.look = model::Vec3(1, 0, 0);
  const auto looking = meter.read(o);
  ASSERT_TRUE(looking.look_distance);
  EXPECT_NEAR(*looking.look_distance, 2.0, 1e-6);
  // The wall's middle: direct I / r^2 (10,000 / 4 pi lm/sr over 4 m2, r = 2.06 m, cos 0.97) plus about
  // flux rho / (S (1 - rho)) of interreflection, times rho / pi: well inside [20, 80] cd/m2.
  EXPECT_GT(looking.circuits[0].look_luminance, 20.0);
  EXPECT_LT(looking.circuits[0].look_luminance, 80.0);
}

// The cube compiled again with `lighting_keys` appended to its [lighting] table: the light stage's report
// line and the light shown, averaged over 300 points spread by area.
struct CubeVariant {
  std::string light_detail;
  double shown = 0.0;
};
CubeVariant compile_cube_with(const fs::path& dir, const std::string& name,
                              const std::string& lighting_keys) {
  std::ifstream in(dir / "cube.toml");
  const std::string scene((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / (name + ".toml")) << scene << lighting_keys;
  std::vector<StageReport> stages;
  CubeVariant out;
  EXPECT_TRUE(
      compile_to_file((dir / (name + ".toml")).string(), (dir / (name + ".walk")).string(), true, &stages));
  const auto light =
      std::find_if(stages.begin(), stages.end(), [](const auto& s) { return s.name == "light"; });
  EXPECT_NE(light, stages.end());
  if (light == stages.end()) return out;
  out.light_detail = light->detail;
  const auto bundle = model::Bundle::open((dir / (name + ".walk")).string());
  const StoredLight stored(*bundle);
  const auto points = surface_points(*bundle, 300);
  for (const auto& p : points) out.shown += stored.on_surface(p.position, p.normal).g / points.size();
  return out;
}

// The closed form of the cube's mean radiosity: rho flux / (S (1 - rho)) W/m2 (179 lm/W).
constexpr double kCubeRadiosity = kRho * kFlux / 179.0 / (6.0 * kSide * kSide * (1.0 - kRho));

TEST_F(ProbeTest, GatheredDirectLightGivesTheSameCube) {
  // The same cube with direct light gathered at the patches' centroids and only reflected light shot: the
  // light shown is the closed form.
  const CubeVariant v = compile_cube_with(dir_, "cube-gather", "direct = \"gather\"\n");
  EXPECT_NE(v.light_detail.find("direct gathered ("), std::string::npos) << v.light_detail;
  std::printf("CIE cube, direct light gathered: shown %.4f, closed form %.4f W/m2\n", v.shown,
              kCubeRadiosity);
  EXPECT_NEAR(v.shown, kCubeRadiosity, 0.03 * kCubeRadiosity);
}

TEST_F(ProbeTest, IndirectLightGatheredAtTheVerticesGivesTheSameCube) {
  // The same cube with direct light gathered and indirect light gathered at each vertex from the solved
  // patches (the final gather): the light shown is again the closed form.
  const CubeVariant v = compile_cube_with(dir_, "cube-final", "direct = \"gather\"\nindirect = \"gather\"\n");
  EXPECT_NE(v.light_detail.find("indirect gathered at vertices ("), std::string::npos) << v.light_detail;
  std::printf("CIE cube, indirect light gathered at vertices: shown %.4f, closed form %.4f W/m2\n", v.shown,
              kCubeRadiosity);
  EXPECT_NEAR(v.shown, kCubeRadiosity, 0.03 * kCubeRadiosity);
}

TEST_F(ProbeTest, TheReferenceFindsPointsNoViewSees) {
  // Under the floor facing up, every first bounce meets the floor's back: hidden, left out of comparisons.
  // Inside the cube facing up, and outside beside it facing away, no bounce meets a back face.
  const PathTracer tracer(*bundle_);
  const auto& m = bundle_->meta();
  const model::Vec3 origin(m.origin[0], m.origin[1], m.origin[2]);  // the tracer works in local metres
  const std::vector<SurfacePoint> points{
      {model::Vec3(2, 2, -0.5) - origin, model::Vec3(0, 0, 1), model::Rgb(0.5)},
      {model::Vec3(2, 2, 0.001) - origin, model::Vec3(0, 0, 1), model::Rgb(0.5)},
      {model::Vec3(-0.5, 2, 2) - origin, model::Vec3(-1, 0, 0), model::Rgb(0.5)}};
  const auto r = tracer.trace(points, 64, 3, 2);
  ASSERT_EQ(r.hidden.size(), 3u);
  EXPECT_EQ(r.hidden[0], 1);
  EXPECT_EQ(r.hidden[1], 0);
  EXPECT_EQ(r.hidden[2], 0);
  EXPECT_GT(r.radiosity[1].g, 0.0);  // lit by the fixture and the walls
  EXPECT_EQ(r.radiosity[2].g, 0.0);  // outside: nothing reaches it
}

TEST_F(ProbeTest, PathTracedReferenceAndDisplayedLightMatchTheClosedForm) {
  // The reference shares no code with the solver: over points spread by area, the mean radiosity is
  // rho E = rho flux / (S (1 - rho)), in W/m2 (the fixture's watts: 10,000 lm at 179 lm/W).
  const auto points = surface_points(*bundle_, 300);
  ASSERT_EQ(points.size(), 300u);
  const PathTracer tracer(*bundle_);
  const StoredLight stored(*bundle_);
  const auto reference = tracer.trace(points, 256, 7, 2);
  double traced = 0.0, shown = 0.0, error2 = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    traced += reference.radiosity[i].g;
    shown += stored.on_surface(points[i].position, points[i].normal).g;
    error2 += reference.standard_error[i] * reference.standard_error[i];
  }
  traced /= points.size();
  shown /= points.size();
  const double expected = kCubeRadiosity;
  std::printf("CIE cube mean radiosity: traced %.4f (+- %.4f), shown %.4f, closed form %.4f W/m2\n", traced,
              std::sqrt(error2) / points.size(), shown, expected);
  // 300 points by area sample the faces' smooth light to about 1 %; the trace's own noise is smaller.
  EXPECT_NEAR(traced, expected, 0.03 * expected);
  EXPECT_NEAR(shown, expected, 0.03 * expected);
  EXPECT_GT(reference.rays, 300u * 256u);
}

}  // namespace test_probe
}  // namespace walk::compiler
