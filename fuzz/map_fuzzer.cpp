// libFuzzer target: the Quake .map reader (parser, brush building, CSG, lights and circuits).
#include <cstddef>
#include <cstdint>
#include <string>

#include "compiler/import/map_reader.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)walk::compiler::read_map_text(std::string(reinterpret_cast<const char*>(data), size), "input.map",
                                        {}, nullptr);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, "input.map");
  }
  return 0;
}
