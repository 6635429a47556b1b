#include "compiler/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include "common/hash.hpp"
#include "compiler/stages/stages.hpp"
#include "model/error.hpp"
#include "model/version.hpp"

namespace walk::compiler {

// The compiler is an input too: its version (git describe) and revision constant. A build from an edited tree
// carries the same version for every edit, so its executable is hashed as well: "up to date" never hides a
// compiler change during development, and a release build does not read its own 60 MB to say who it is.
std::uint64_t compiler_identity() {
  static const std::uint64_t identity = [] {
    const std::string v = version();
    std::uint64_t h = hash_bytes(kCompilerRevision, v.data(), v.size());
    if (v.find("dirty") != std::string::npos || v.find("+git.") == std::string::npos)
      h = hash_file(h, "/proc/self/exe");
    return h;
  }();
  return identity;
}

std::uint64_t scene_hash(const SceneConfig& config) {
  std::uint64_t h = compiler_identity();
  h = hash_bytes(h, config.text.data(), config.text.size());
  h = hash_file(h, config.model_file);
  // What a mesh model reads beside itself (its .mtl, albedo maps) and the scene's texture folders: an
  // edited texture must recompile, not be taken for the bundle's own.
  std::vector<std::filesystem::path> folders{std::filesystem::path(config.model_file).parent_path()};
  for (const auto& d : config.texture_dirs) folders.emplace_back(d);
  for (const auto& folder : folders) {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
      std::string ext = entry.path().extension().string();
      for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (ext == ".mtl" || ext == ".png" || ext == ".jpg" || ext == ".jpeg") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) h = hash_file(h, f.string());
  }
  return h;
}

CompileResult compile_scene(const SceneConfig& config, const CompileOptions& options,
                            const model::Bundle* previous) {
  CompileResult result;
  CompileState state(config, options, previous, result.bundle);
  for (const auto& stage : compile_stages()) {
    const auto start = std::chrono::steady_clock::now();
    StageReport report;
    report.name = stage->name();
    report.input_hash = stage->input_hash(state);
    const StageOutcome outcome = stage->run(state, report.input_hash);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.detail = outcome.detail;
    report.estimated_error = outcome.estimated_error;
    switch (outcome.kind) {
      case StageOutcome::Kind::Ran:
        report.ran = true;
        report.items_in = outcome.items_in;
        report.items_out = outcome.items_out;
        spdlog::info("stage {}: {} -> {} in {:.3f} s {}", report.name, report.items_in, report.items_out,
                     report.seconds, report.detail);
        break;
      case StageOutcome::Kind::Reused:
        report.reused = true;
        spdlog::info("stage {}: reused ({})", report.name, report.detail);
        break;
      case StageOutcome::Kind::Skipped:
        spdlog::info("stage {}: not run ({})", report.name, report.detail);
        break;
    }
    result.stages.push_back(std::move(report));
  }
  auto& out = result.bundle;
  for (const auto& s : result.stages)
    out.stages.push_back({out.add_string(s.name), s.ran ? 1u : (s.reused ? 2u : 0u),
                          s.input_hash != 0 ? s.input_hash : out.meta.scene_hash, s.seconds, s.items_in,
                          s.items_out});
  return result;
}

bool compile_to_file(const std::string& config_path, const std::string& output, bool force,
                     std::vector<StageReport>* stages, const CompileOptions& options) {
  const SceneConfig config = load_scene_config(config_path);
  std::unique_ptr<model::Bundle> previous;
  if (std::filesystem::exists(output)) {
    try {
      previous = model::Bundle::open(output);
    } catch (const Error& e) {
      spdlog::info("previous bundle not reusable: {}", e.what());  // an unreadable old bundle is rebuilt
    }
  }
  if (!force && previous && previous->meta().scene_hash == scene_hash(config)) return false;
  CompileResult result = compile_scene(config, options, force ? nullptr : previous.get());
  previous.reset();  // unmap before the rename replaces the file
  model::write_bundle(output, result.bundle);
  if (stages) *stages = std::move(result.stages);
  return true;
}

}  // namespace walk::compiler
