// libFuzzer target: the IES LM-63 and EULUMDAT readers (the first byte picks one). A table they accept must
// give finite, non-negative candela and a finite flux; a rejection must name the file and line.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "compiler/photometry/eulumdat_reader.hpp"
#include "compiler/photometry/ies_reader.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool ies = data[0] % 2 == 0;
  const std::string file = ies ? "input.ies" : "input.ldt";
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const auto d = ies ? walk::compiler::parse_ies(text, file) : walk::compiler::parse_eulumdat(text, file);
    if (!std::isfinite(d.lumens) || d.lumens < 0.0) std::abort();
    for (double g : {0.0, 33.0, 90.0, 179.0})
      for (double c : {0.0, 45.0, 200.0, 359.0}) {
        const double v = d.candela_at(g, c);
        if (!std::isfinite(v) || v < 0.0) std::abort();
      }
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, file);
  }
  return 0;
}
