// The libFuzzer targets for the DXF and .map parsers (fuzz/), built with clang and run for a bounded time
// (WALK_FUZZ_SECONDS, default 30 s each) on the committed seed corpus: no crash, no hang, and every rejection
// a walk::Error naming file and line. Skipped where clang cannot link libFuzzer.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace walk::compiler {
namespace {

TEST(ImportFuzz, DxfAndMapParsersSurviveBoundedFuzzing) {
  const char* env = std::getenv("WALK_FUZZ_SECONDS");
  const std::string seconds = env && *env ? env : "30";
  const std::string out = std::string(WALK_BINARY_DIR) + "/fuzz";
  const std::string command = "bash '" + std::string(WALK_SOURCE_DIR) + "/fuzz/run_fuzzers.sh' '" +
                              WALK_SOURCE_DIR + "' '" + out + "' " + seconds + " > '" + out + ".log' 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 77) GTEST_SKIP() << "no clang with libFuzzer (see " << out << ".log)";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "fuzzing failed: see " << out << ".log and " << out << "/*_fuzzer.log";
}

}  // namespace
}  // namespace walk::compiler
