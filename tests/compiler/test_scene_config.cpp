// Scene config errors name the file, the line and the key.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/raycast/embree_caster.hpp"
#include "compiler/scene/scene_config.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace test_scene_config {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class SceneConfigTest : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    path_ = (fs::temp_directory_path() / ("walk_scene_" + std::to_string(::getpid()) + ".toml")).string();
    std::ofstream(path_) << text;
    return path_;
  }
  std::string error_of(const std::string& text) {
    try {
      (void)load_scene_config(write(text));
    } catch (const Error& e) {
      return e.what();
    }
    return {};
  }
  void TearDown() override { fs::remove(path_); }
  std::string path_;
};

TEST_F(SceneConfigTest, DirectLightIsShotUnlessToldAndRefinedOnlyWhenAsked) {
  const std::string head = "[model]\nfile = \"a.obj\"\n";
  const auto plain = load_scene_config(write(head));
  EXPECT_FALSE(plain.lighting.gather_direct);
  EXPECT_FALSE(plain.lighting.refine);
  const auto gathered = load_scene_config(write(head + "[lighting]\ndirect = \"gather\"\nrefine = true\n"));
  EXPECT_TRUE(gathered.lighting.gather_direct);
  EXPECT_TRUE(gathered.lighting.refine);
  const std::string way = error_of(head + "[lighting]\ndirect = \"both\"\n");
  EXPECT_NE(way.find("lighting.direct"), std::string::npos) << way;
  EXPECT_NE(way.find("known: gather, shoot"), std::string::npos) << way;
  EXPECT_NE(error_of(head + "[lighting]\nrefine = \"yes\"\n").find("lighting.refine"), std::string::npos);
}

TEST_F(SceneConfigTest, IndirectLightIsGatheredOnlyWhenAskedAndOnlyWithGatheredDirectLight) {
  const std::string head = "[model]\nfile = \"a.obj\"\n";
  EXPECT_FALSE(load_scene_config(write(head)).lighting.gather_indirect);
  const auto final_gather =
      load_scene_config(write(head + "[lighting]\ndirect = \"gather\"\nindirect = \"gather\"\n"));
  EXPECT_TRUE(final_gather.lighting.gather_indirect);
  EXPECT_FALSE(load_scene_config(write(head + "[lighting]\ndirect = \"gather\"\nindirect = \"patches\"\n"))
                   .lighting.gather_indirect);
  const std::string alone = error_of(head + "[lighting]\nindirect = \"gather\"\n");
  EXPECT_NE(alone.find("lighting.indirect"), std::string::npos) << alone;
  EXPECT_NE(alone.find("direct = \"gather\""), std::string::npos) << alone;
  const std::string way = error_of(head + "[lighting]\ndirect = \"gather\"\nindirect = \"trace\"\n");
  EXPECT_NE(way.find("known: gather, patches"), std::string::npos) << way;
}

TEST_F(SceneConfigTest, StartIsInModelUnitsAndOptional) {
  const auto none = load_scene_config(write("[model]\nfile = \"a.dxf\"\nunits = \"m\"\n"));
  EXPECT_FALSE(none.start.has_value());
  const auto cfg =
      load_scene_config(write("[model]\nfile = \"a.obj\"\nunits = \"mm\"\n[start]\nposition = [1000, -500, "
                              "2600]\nheading_deg = 90\n"));
  ASSERT_TRUE(cfg.start.has_value());
  EXPECT_NEAR(cfg.start->position.x, 1.0, 1e-12);
  EXPECT_NEAR(cfg.start->position.y, -0.5, 1e-12);
  EXPECT_NEAR(cfg.start->position.z, 2.6, 1e-12);
  EXPECT_NEAR(cfg.start->heading, std::acos(0.0), 1e-12);
  const std::string missing = error_of("[model]\nfile = \"a.obj\"\n[start]\nheading_deg = 90\n");
  EXPECT_NE(missing.find("start.position"), std::string::npos) << missing;
  const std::string typo =
      error_of("[model]\nfile = \"a.obj\"\n[start]\nposition = [0, 0, 0]\nheading = 1\n");
  EXPECT_NE(typo.find("start.heading"), std::string::npos) << typo;
}

TEST_F(SceneConfigTest, UnknownUnitNamesKeyLineAndKnownUnits) {
  const std::string e = error_of("[model]\nfile = \"a.dxf\"\nunits = \"furlong\"\n");
  EXPECT_NE(e.find(path_ + ":3"), std::string::npos) << e;
  EXPECT_NE(e.find("model.units"), std::string::npos) << e;
  EXPECT_NE(e.find("furlong"), std::string::npos) << e;
  EXPECT_NE(e.find("mm"), std::string::npos) << e;
}

TEST_F(SceneConfigTest, SyntaxErrorNamesLine) {
  const std::string e = error_of("[model]\nfile = \"a.dxf\"\nunits = = 3\n");
  EXPECT_NE(e.find(path_ + ":3"), std::string::npos) << e;
}

TEST_F(SceneConfigTest, MisspeltKeyIsRefused) {
  const std::string e = error_of("[model]\nfile = \"a.dxf\"\nunit = \"m\"\n");
  EXPECT_NE(e.find("unknown key 'model.unit'"), std::string::npos) << e;
}

TEST_F(SceneConfigTest, BadRuleFieldsAreRefused) {
  EXPECT_NE(error_of("[model]\nfile = \"a.dxf\"\n[[rules]]\nname = \"(\"\nrole = \"glass\"\n")
                .find("rules[0].name"),
            std::string::npos);
  EXPECT_NE(error_of("[model]\nfile = \"a.dxf\"\n[[rules]]\nrole = \"window\"\n").find("unknown role"),
            std::string::npos);
  EXPECT_NE(error_of("[model]\nfile = \"a.dxf\"\n[[rules]]\nrole = \"glass\"\nmaterial = \"pane\"\n")
                .find("material 'pane'"),
            std::string::npos);
  EXPECT_NE(error_of("[model]\nfile = \"a.dxf\"\n[materials.wall]\nreflectance = [0.5, 1.5, 0.5]\n")
                .find("between 0 and 1"),
            std::string::npos);
}

TEST_F(SceneConfigTest, MissingModelTable) {
  EXPECT_NE(error_of("[lighting]\ngrid = 1\n").find("[model]"), std::string::npos);
}

TEST_F(SceneConfigTest, ModelPathIsResolvedAgainstTheConfigFolder) {
  write("[model]\nfile = \"sub/a.dxf\"\nunits = \"in\"\n");
  const SceneConfig c = load_scene_config(path_);
  EXPECT_EQ(fs::path(c.model_file), fs::path(path_).parent_path() / "sub" / "a.dxf");
  EXPECT_DOUBLE_EQ(c.metres_per_unit, 0.0254);
}

// Toml++ 3.3 (Debian 12) reaches TOML_UNREACHABLE in its whitespace test for code points in U+00A1..U+0499,
// U+2C3E..U+3037 and U+FB26..U+FEFE (fuzz/scene_toml_fuzzer under UBSan). In the shipped build such
// characters parse as the text they are: a config using them keeps working.
TEST_F(SceneConfigTest, NonAsciiNamesAndCommentsLoadAsWritten) {
  write(
      "[model]\nfile = \"a.obj\"\n# B\xc3\xa9ton, \xe3\x80\x81 and \xef\xbb\xbb in a comment\n"
      "[materials.\"B\xc3\xa9ton \xc8\x8a\xef\xbb\xbb\"]\nreflectance = [0.5, 0.5, 0.5]\n");
  const SceneConfig c = load_scene_config(path_);
  ASSERT_EQ(c.materials.size(), 2u);
  EXPECT_EQ(c.materials[1].name, "B\xc3\xa9ton \xc8\x8a\xef\xbb\xbb");
}

TEST_F(SceneConfigTest, TextureFoldersAreResolvedAndMustExist) {
  const fs::path folder = fs::temp_directory_path() / ("walk_scene_maps_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  write("[model]\nfile = \"a.obj\"\ntextures = [\"" + folder.filename().string() + "\"]\n");
  EXPECT_EQ(load_scene_config(path_).texture_dirs, std::vector<std::string>{folder.string()});
  fs::remove(folder);
  for (const std::string bad : {"[\"no_such_maps_folder\"]", "\"maps\"", "[1]"}) {
    const std::string err = error_of("[model]\nfile = \"a.obj\"\ntextures = " + bad + "\n");
    EXPECT_NE(err.find("textures"), std::string::npos) << bad << ": " << err;
    EXPECT_NE(err.find(":3"), std::string::npos) << bad << " names the line: " << err;
  }
}

// A [model] length in metres: `good` is read as it is, leaving it out gives 0, and each of `bad` is refused
// with an error naming the key.
struct MetresKey {
  const char* key;
  double SceneConfig::*field;
  double good;
  std::vector<const char*> bad;
};

TEST_F(SceneConfigTest, WeldAndSealAreMetresAndBounded) {
  // weld 0: relative to the model's size; seal 0: no sealing.
  for (const MetresKey& k : {MetresKey{"weld", &SceneConfig::weld_metres, 2e-5, {"0", "-1e-5", "0.5"}},
                             MetresKey{"seal", &SceneConfig::seal_metres, 0.03, {"0", "-0.01", "0.5"}}}) {
    write(std::string("[model]\nfile = \"a.dxf\"\n") + k.key + " = " + std::to_string(k.good) + "\n");
    EXPECT_DOUBLE_EQ(load_scene_config(path_).*k.field, k.good) << k.key;
    write("[model]\nfile = \"a.dxf\"\n");
    EXPECT_EQ(load_scene_config(path_).*k.field, 0.0) << k.key;
    for (const char* bad : k.bad) {
      const std::string e = error_of(std::string("[model]\nfile = \"a.dxf\"\n") + k.key + " = " + bad + "\n");
      EXPECT_NE(e.find(std::string("model.") + k.key), std::string::npos) << bad << ": " << e;
    }
  }
}

TEST_F(SceneConfigTest, ProofPairsAreACountOrNone) {
  write("[model]\nfile = \"a.dxf\"\n[visibility]\nproof_pairs = 16\n");
  EXPECT_EQ(load_scene_config(path_).visibility.proof_pairs, 16);
  write("[model]\nfile = \"a.dxf\"\n[visibility]\nproof_pairs = 0\n");
  EXPECT_EQ(load_scene_config(path_).visibility.proof_pairs, 0) << "no proofs";
  write("[model]\nfile = \"a.dxf\"\n");
  EXPECT_EQ(load_scene_config(path_).visibility.proof_pairs, VisibilityConfig{}.proof_pairs);
  for (const char* bad : {"-1", "2000000", "1.5"}) {
    const std::string e =
        error_of(std::string("[model]\nfile = \"a.dxf\"\n[visibility]\nproof_pairs = ") + bad + "\n");
    EXPECT_NE(e.find("visibility.proof_pairs"), std::string::npos) << bad << ": " << e;
  }
}

TEST_F(SceneConfigTest, DetailRulesAreSizesAndGroupPatterns) {
  write(
      "[model]\nfile = \"a.dxf\"\n[visibility]\ndetail_extent = 2.0\ndetail_area = 0\n"
      "structure = \"^shell\"\ndetail = \"chair|table\"\n");
  const SceneConfig c = load_scene_config(path_);
  EXPECT_EQ(c.visibility.detail_extent, 2.0);
  EXPECT_EQ(c.visibility.detail_area, 0.0);
  ASSERT_TRUE(c.visibility.structure_groups && c.visibility.detail_groups);
  EXPECT_TRUE(std::regex_search("shell north", *c.visibility.structure_groups));
  EXPECT_TRUE(std::regex_search("room 2 table 4", *c.visibility.detail_groups));
  write("[model]\nfile = \"a.dxf\"\n");
  EXPECT_FALSE(load_scene_config(path_).visibility.detail_groups);
  for (const auto& [key, bad] : {std::pair{"detail_extent", "-1"}, std::pair{"detail_area", "-0.5"},
                                 std::pair{"detail", "\"(chair\""}, std::pair{"structure", "3"}}) {
    const std::string e =
        error_of(std::string("[model]\nfile = \"a.dxf\"\n[visibility]\n") + key + " = " + bad + "\n");
    EXPECT_NE(e.find(std::string("visibility.") + key), std::string::npos)
        << key << " = " << bad << ": " << e;
  }
}

// A ray caster is checked against this build's; plain Embree is accepted with a warning naming the file,
// since it breaks the self-hit policy, and embree-exact is not.
TEST_F(SceneConfigTest, RayCastersAreCheckedAndPlainEmbreeIsWarnedOf) {
  const std::string e = error_of("[model]\nfile = \"a.dxf\"\n[lighting]\nray_caster = \"optix\"\n");
  EXPECT_NE(e.find("unknown ray caster 'optix'"), std::string::npos) << e;
  if (!embree_available()) {
    EXPECT_NE(error_of("[model]\nfile = \"a.dxf\"\n[visibility]\nray_caster = \"embree-exact\"\n")
                  .find("unknown ray caster"),
              std::string::npos);
    return;
  }
  std::ostringstream log;
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("capture", std::make_shared<spdlog::sinks::ostream_sink_st>(log)));
  for (const char* table : {"lighting", "visibility"}) {
    for (const char* caster : {"embree-exact", "embree"}) {
      log.str("");
      write(std::string("[model]\nfile = \"a.dxf\"\n[") + table + "]\nray_caster = \"" + caster + "\"\n");
      const SceneConfig c = load_scene_config(path_);
      EXPECT_EQ(std::string(table) == "lighting" ? c.lighting.ray_caster : c.visibility.ray_caster, caster);
      const bool warned = log.str().find("self-hit policy") != std::string::npos;
      EXPECT_EQ(warned, std::string(caster) == "embree") << table << " " << caster << ": " << log.str();
      if (warned) {
        EXPECT_NE(log.str().find(path_), std::string::npos) << log.str();
      }
    }
  }
  spdlog::set_default_logger(previous);
}

TEST_F(SceneConfigTest, ShippedScenesLoad) {
  for (const char* name : {"house.toml", "medium-office.toml"}) {
    const SceneConfig c = load_scene_config(std::string(WALK_SOURCE_DIR) + "/config/scenes/" + name);
    EXPECT_TRUE(fs::exists(c.model_file)) << c.model_file;
    EXPECT_TRUE(c.panels.enabled);
    EXPECT_FALSE(c.rules.empty());
  }
}

TEST_F(SceneConfigTest, PanelsFacingAnyWayAreFlatRectanglesFacingTheirNormal) {
  // Along x (where the width axis used to collapse), tilted, and straight down.
  const auto cfg =
      load_scene_config(write("[model]\nfile = \"a.obj\"\n"
                              "[[luminaires.panel]]\nposition = [0, 0, 2]\nnormal = [-1, 0, 0]\n"
                              "[[luminaires.panel]]\nposition = [0, 0, 2]\nnormal = [1, 0, -1]\n"
                              "[[luminaires.panel]]\nposition = [0, 0, 2]\nnormal = [0, 0, -3]\n"));
  ASSERT_EQ(cfg.luminaires.size(), 3u);
  for (const auto& l : cfg.luminaires) {
    EXPECT_NEAR(glm::length(l.normal), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(l.u_axis), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(l.u_axis, l.normal), 0.0, 1e-12);  // width lies in the panel's plane
  }
  EXPECT_NEAR(cfg.luminaires[2].u_axis.x, 1.0, 1e-12);  // a ceiling panel keeps its width along x
}

TEST_F(SceneConfigTest, PanelSizesAndDropsThatMakeNoPanelAreRefused) {
  const std::string flat =
      error_of("[model]\nfile = \"a.obj\"\n[[luminaires.panel]]\nposition = [0, 0, 2]\nsize = [0.6, 0]\n");
  EXPECT_NE(flat.find("luminaires.panel[0].size"), std::string::npos) << flat;
  EXPECT_NE(flat.find(":5"), std::string::npos) << flat;
  const std::string above = error_of("[model]\nfile = \"a.obj\"\n[luminaires.per_group]\ndrop = -0.1\n");
  EXPECT_NE(above.find("luminaires.per_group.drop"), std::string::npos) << above;
}

}  // namespace test_scene_config
}  // namespace walk::compiler

namespace walk::compiler {
namespace test_scene_config {  // named, not anonymous: the suite compiles as unity batches

// Luminaires in photometric terms: lumens, colour temperature, measured distributions, white luminance.
class PhotometricSceneTest : public SceneConfigTest {
 protected:
  void SetUp() override {
    ies_ = (fs::temp_directory_path() / ("walk_fixture_" + std::to_string(::getpid()) + ".ies")).string();
    // Isotropic 100 cd: 400 pi lm.
    std::ofstream(ies_)
        << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n100 100 100\n";
  }
  void TearDown() override {
    fs::remove(ies_);
    SceneConfigTest::TearDown();
  }
  std::string ies_;
};

double luminance_of(const model::Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

TEST_F(PhotometricSceneTest, FixturesPanelsAndExposureInPhotometricUnits) {
  const std::string name = fs::path(ies_).filename().string();
  const auto cfg = load_scene_config(
      write("[model]\nfile = \"a.obj\"\n[lighting]\nwhite_luminance = 100\n"
            "[[luminaires.panel]]\nposition = [0, 0, 3]\nflux = 1790\ncct = 3000\n"
            "[[luminaires.fixture]]\nname = \"down\"\nposition = [1, 0, 3]\nphotometry = \"" +
            name +
            "\"\n"
            "[[luminaires.fixture]]\nposition = [2, 0, 3]\nphotometry = \"" +
            name + "\"\nflux = 179\naim = [0, 1, 0]\n"));
  ASSERT_EQ(cfg.luminaires.size(), 3u);
  const auto& panel = cfg.luminaires[0];
  EXPECT_NEAR(luminance_of(panel.power), 10.0, 1e-9);  // 1790 lm at 179 lm/W
  EXPECT_GT(panel.power.r, panel.power.b);             // 3000 K is warm
  const auto& down = cfg.luminaires[1];
  EXPECT_EQ(down.kind, model::LuminaireKind::Photometric);
  ASSERT_TRUE(down.distribution);
  EXPECT_NEAR(luminance_of(down.power), 400.0 * std::acos(-1.0) / 179.0, 1e-3);  // the file's own flux
  EXPECT_EQ(cfg.luminaires[2].distribution, down.distribution);                  // one file, read once
  EXPECT_NEAR(luminance_of(cfg.luminaires[2].power), 1.0, 1e-9);                 // `flux` rescales the table
  EXPECT_NEAR(cfg.luminaires[2].normal.y, 1.0, 1e-12);
  ASSERT_TRUE(cfg.lighting.exposure);
  EXPECT_NEAR(*cfg.lighting.exposure, 100.0 * std::acos(-1.0) / 179.0, 1e-12);
}

TEST_F(PhotometricSceneTest, BadPhotometricKeysNameTheKeyAndTheFile) {
  const std::string head = "[model]\nfile = \"a.obj\"\n";
  const std::string both =
      error_of(head + "[[luminaires.panel]]\nposition = [0, 0, 3]\npower = 5\nflux = 100\n");
  EXPECT_NE(both.find("luminaires.panel"), std::string::npos) << both;
  EXPECT_NE(both.find("not both"), std::string::npos) << both;
  const std::string cold = error_of(head + "[luminaires.per_group]\ncct = 500\n");
  EXPECT_NE(cold.find("luminaires.per_group.cct"), std::string::npos) << cold;
  const std::string missing =
      error_of(head + "[[luminaires.fixture]]\nposition = [0, 0, 3]\nphotometry = \"nowhere.ies\"\n");
  EXPECT_NE(missing.find("photometry"), std::string::npos) << missing;
  EXPECT_NE(missing.find("nowhere.ies"), std::string::npos) << missing;
  std::ofstream(ies_)
      << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n100 lots 100\n";
  const std::string bad = error_of(head + "[[luminaires.fixture]]\nposition = [0, 0, 3]\nphotometry = \"" +
                                   fs::path(ies_).filename().string() + "\"\n");
  EXPECT_NE(bad.find(":7: 'lots' where a candela value should be"), std::string::npos) << bad;
  const std::string target = error_of(head + "[lighting]\nrays_per_watt = 10\ntarget_error = 0.05\n");
  EXPECT_NE(target.find("lighting.target_error"), std::string::npos) << target;
  EXPECT_NE(target.find("not both"), std::string::npos) << target;
  const std::string tiny = error_of(head + "[lighting]\ntarget_error = 0.00001\n");
  EXPECT_NE(tiny.find("must be between 0.001 and 0.5"), std::string::npos) << tiny;
  const std::string exposure = error_of(head + "[lighting]\nexposure = 1\nwhite_luminance = 100\n");
  EXPECT_NE(exposure.find("lighting.white_luminance"), std::string::npos) << exposure;
  const std::string c0 = error_of(head +
                                  "[[luminaires.fixture]]\nposition = [0, 0, 3]\nc0 = [0, 0, 1]\n"
                                  "photometry = \"x.ies\"\n");
  EXPECT_NE(c0.find("luminaires.fixture[0].c0"), std::string::npos) << c0;
}

}  // namespace test_scene_config
}  // namespace walk::compiler
