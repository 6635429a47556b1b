// libFuzzer target: scene configs (TOML through toml++ and our accessor, every table and key the compiler
// reads). Rejections must name the file (and the line where TOML gives one).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"
#include "compiler/scene/scene_config.hpp"
#include "fuzz/fuzz_check.hpp"

// The scene reader checks `ray_caster` against this build's casters; the fuzz build links none of them.
std::vector<std::string> walk::compiler::ray_caster_names() {
  return {"axial", "bvh", "brute"};
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "input-" + std::to_string(::getpid()) + ".toml";
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    (void)walk::compiler::load_scene_config(path);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, path);
  }
  return 0;
}
