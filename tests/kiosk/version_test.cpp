// Every program answers --version with its name and the build's version (the project's and git describe),
// and a bundle records the `walk` that compiled it, which `walk inspect` prints.
#include "model/version.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "model/bundle.hpp"

namespace walk::kiosk {
namespace version_test {  // named, not anonymous: the suite compiles as unity batches

std::string output_of(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  std::array<char, 256> buffer{};
  while (std::fgets(buffer.data(), int(buffer.size()), pipe)) out += buffer.data();
  ::pclose(pipe);
  return out;
}

TEST(Version, EveryProgramPrintsItsNameAndTheBuildsVersion) {
  EXPECT_EQ(std::string(version()).rfind("0.1.0", 0), 0u) << version();
  for (const auto& [program, name] : {std::pair{"/tools/walk", "walk"},
                                      {"/firmware-host/walkd", "walkd"},
                                      {"/devices/walk-panel-sim", "walk-panel-sim"}}) {
    const std::string out = output_of(std::string(WALK_BINARY_DIR) + program + " --version");
    EXPECT_EQ(out, std::string(name) + " " + version() + "\n") << program;
  }
}

TEST(Version, BundleRecordsTheCompilerAndInspectPrintsIt) {
  const auto dir = std::filesystem::temp_directory_path() / ("walk_version_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string bundle = (dir / "house.walk").string();
  const std::string walk = std::string(WALK_BINARY_DIR) + "/tools/walk";
  (void)output_of(walk + " compile " + WALK_SOURCE_DIR + "/config/scenes/house.toml -o " + bundle);
  const auto opened = model::Bundle::open(bundle);
  EXPECT_EQ(opened->string(opened->meta().compiler_version), std::string("walk ") + version());
  EXPECT_NE(output_of(walk + " inspect " + bundle).find(std::string("compiled by       walk ") + version()),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace version_test
}  // namespace walk::kiosk
