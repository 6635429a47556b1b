// libFuzzer target: OBJ through the mesh reader (assimp parses, our code turns its scene into polygons,
// materials, luminaires and texture maps). assimp itself is Debian's, not instrumented; what is checked is
// that whatever it hands back, our conversion neither crashes nor rejects without naming the file, and that
// what the import stage passes on (read_mesh, then check_coordinates, as import_stage.cpp runs them) has
// finite vertices only: a NaN or 1e308 corner is an error naming the file and line, never a polygon kept.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "compiler/cleanup/stray_geometry.hpp"
#include "compiler/import/mesh_reader.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "input-" + std::to_string(::getpid()) + ".obj";
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  walk::compiler::MeshOptions options;
  options.y_up = size % 2 == 0;
  walk::compiler::MeshStats stats;
  try {
    const walk::model::Model model = walk::compiler::read_mesh(path, options, &stats);
    walk::compiler::check_coordinates(model, path);
    for (const auto& p : model.polygons)
      for (const auto& v : p.vertices)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
          std::fprintf(stderr, "non-finite vertex kept from %s\n", path.c_str());
          std::abort();
        }
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, path);
  }
  return 0;
}
