// libFuzzer target: kiosk configs (TOML through toml++ and walkd's Section accessor: display, screens,
// steering, every device backend and report layout). Rejections must name the file (and the line where
// TOML gives one); nothing a config says may crash walkd before it starts.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "firmware-host/kiosk_config.hpp"
#include "fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "input-" + std::to_string(::getpid()) + ".toml";
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    (void)walk::kiosk::load_kiosk_config(path);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, path);
  }
  return 0;
}
