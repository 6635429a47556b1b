// libFuzzer target: the DXF reader (tokenizer, sections, blocks, every entity type, INSERT expansion).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "compiler/import/dxf_reader.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<walk::compiler::DxfWire> wires;
  try {
    (void)walk::compiler::read_dxf(in, "input.dxf", {1.0, true}, nullptr, &wires);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, "input.dxf");
  }
  return 0;
}
