// The libFuzzer targets (fuzz/: DXF, .map, bundle reader with checksums repaired, CSV traces, HID reports,
// Modbus registers, scene and kiosk TOML configs), built with
// clang and run for a bounded time (WALK_FUZZ_SECONDS, default 30 s each) on the committed seed corpus: no
// crash, no hang, and every rejection a walk::Error naming file and line. Skipped where clang cannot link
// libFuzzer.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace walk::compiler {
namespace test_import_fuzz {  // named, not anonymous: the suite compiles as unity batches

TEST(ImportFuzz, ParsersSurviveBoundedFuzzing) {
  const char* env = std::getenv("WALK_FUZZ_SECONDS");
  const std::string seconds = env && *env ? env : "30";
  const std::string out = std::string(WALK_BINARY_DIR) + "/fuzz";
  const std::string command = "bash '" + std::string(WALK_SOURCE_DIR) + "/fuzz/run_fuzzers.sh' '" +
                              WALK_SOURCE_DIR + "' '" + out + "' " + seconds + " > '" + out + ".log' 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 77) GTEST_SKIP() << "no clang with libFuzzer (see " << out << ".log)";
  if (WEXITSTATUS(status) != 0) {
    // CI keeps only the test's own output: print the script's report (log tail and the failing input in
    // base64) here, not just where it lies on a machine that is gone.
    std::ifstream log(out + ".log");
    const std::string report((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    ADD_FAILURE() << "fuzzing failed (exit " << WEXITSTATUS(status) << "); " << out << ".log says:\n"
                  << report;
  }
}

}  // namespace test_import_fuzz
}  // namespace walk::compiler
