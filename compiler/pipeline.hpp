#pragma once
// The display compiler: scene config -> the stages of compiler/stages/stages.hpp in order (import, rules,
// cleanup, recentre, openings, seal, luminaires, mesh, light, compact, meta, cells, lod) -> bundle. Each
// stage records what it did; a stage the scene does not call for is not run.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/scene/scene_config.hpp"
#include "model/bundle.hpp"

namespace walk::compiler {

// Bumped whenever the compiler's output for the same inputs changes, so old bundles are rebuilt.
inline constexpr std::uint32_t kCompilerRevision = 1;

struct StageReport {
  std::string name;
  bool ran = false;
  bool reused = false;  // not run: its inputs were unchanged, so its output came from the previous bundle
  std::uint64_t input_hash = 0;
  double seconds = 0.0;
  std::uint64_t items_in = 0;
  std::uint64_t items_out = 0;
  std::string detail;
  std::optional<double> estimated_error;  // light stage: the solver's own relative error estimate
};

struct CompileOptions {
  unsigned threads = 2;
};

struct CompileResult {
  model::BundleContents bundle;
  std::vector<StageReport> stages;
};

// The compiler's own identity, an input of every hash: version, revision, and for a development build its
// executable.
[[nodiscard]] std::uint64_t compiler_identity();

// Hash of everything the output depends on: config bytes, model file bytes, compiler revision.
[[nodiscard]] std::uint64_t scene_hash(const SceneConfig& config);

// `previous`, when given, is the bundle this compile replaces: a stage whose inputs hash the same as there
// takes its output from it instead of running again (the light solve, chiefly).
[[nodiscard]] CompileResult compile_scene(const SceneConfig& config, const CompileOptions& options = {},
                                          const model::Bundle* previous = nullptr);

// Compiles `config_path` into `output` unless `output` already holds a bundle of the same scene hash
// (returns false then). Never leaves a partial bundle behind.
bool compile_to_file(const std::string& config_path, const std::string& output, bool force,
                     std::vector<StageReport>* stages = nullptr, const CompileOptions& options = {});

}  // namespace walk::compiler
