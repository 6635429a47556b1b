// The unit file must pass `systemd-analyze verify` with no output at all (it warns yet exits 0), the sysusers
// entry must parse, and the sandbox must stay tight. systemd/verify-unit.sh does the work.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace systemd_unit_test {  // named, not anonymous: the suite compiles as unity batches

TEST(SystemdUnit, VerifiesWithoutAnyOutput) {
  if (std::system("command -v systemd-analyze >/dev/null 2>&1") != 0) GTEST_SKIP() << "no systemd-analyze";
  const std::string walkd = WALK_BINARY_DIR "/firmware-host/walkd";
  const auto log = std::filesystem::temp_directory_path() / "walk_verify_unit.log";
  const std::string command = "sh " WALK_SOURCE_DIR "/systemd/verify-unit.sh " +
                              (std::filesystem::exists(walkd) ? walkd : std::string()) + " > " +
                              log.string() + " 2>&1";
  const int rc = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(log);
  EXPECT_EQ(rc, 0) << text.str();
  EXPECT_EQ(text.str().find("FAIL"), std::string::npos) << text.str();
}

}  // namespace systemd_unit_test
