// Added luminaires and circuits on top of what an importer found.
#include <gtest/gtest.h>

#include "compiler/import/dxf_reader.hpp"
#include "compiler/scene/apply_rules.hpp"
#include "compiler/scene/luminaires.hpp"

namespace walk::compiler {
namespace test_luminaires {  // named, not anonymous: the suite compiles as unity batches

TEST(Luminaires, ImportedLightsKeepTheirCircuitBesideAddedPanels) {
  const SceneConfig config = load_scene_config(std::string(WALK_SOURCE_DIR) + "/config/scenes/house.toml");
  model::Model m = read_dxf(config.model_file);
  (void)apply_rules(m, config);
  // As an importer would leave them: two point lights on one switched circuit that starts off.
  m.circuits.push_back({"switch hall", 0.0});
  for (int i = 0; i < 2; ++i) {
    model::Luminaire l;
    l.kind = model::LuminaireKind::Point;
    l.name = "light" + std::to_string(i);
    l.circuit = 0;
    m.luminaires.push_back(l);
  }
  const LuminaireStats s = add_luminaires(m, config);
  EXPECT_EQ(s.added_per_group, 16u);
  ASSERT_EQ(m.luminaires.size(), 18u);
  ASSERT_EQ(m.circuits.size(), 17u);  // the imported circuit plus one per room
  EXPECT_EQ(m.circuits[m.luminaires[0].circuit].name, "switch hall");
  EXPECT_EQ(m.luminaires[0].circuit, m.luminaires[1].circuit);
  EXPECT_EQ(m.circuits[m.luminaires[0].circuit].default_level, 0.0);
  for (const auto& l : m.luminaires) EXPECT_LT(l.circuit, m.circuits.size());
}

}  // namespace test_luminaires
}  // namespace walk::compiler
