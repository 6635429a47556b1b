// libFuzzer target: the CSV traces the mock devices replay (treadmill, head tracker, dimmer panel columns).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "devices/mock/csv_trace.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "input-" + std::to_string(::getpid()) + ".csv";
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    const auto trace =
        walk::devices::CsvTrace::load(path, {"speed"}, {"steer_deg", "yaw_deg"}, size % 2 == 0);
    for (std::size_t r = 0; r < trace.size(); ++r)
      for (std::size_t c = 0; c < trace.columns().size(); ++c) (void)trace.value(r, c);
    (void)trace.row_at(trace.size() ? trace.time(trace.size() - 1) : 0.0);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, path);
  }
  return 0;
}
