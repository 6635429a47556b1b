// libFuzzer target: the bundle reader. Before each input is opened, its header's version, file size and
// every checksum are made right (where the input is long enough to hold them), so the fuzzer reaches the
// checks behind the checksums: forged counts, ranges, cross-references and statistics must be rejected
// with an error naming the file, never read out of bounds.
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/fuzz_check.hpp"
#include "model/bundle.hpp"

namespace {

std::uint32_t crc(const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), data, static_cast<uInt>(size)));
}

// Fixes what a random mutation almost never gets right, leaving everything else as the input says.
void repair_checksums(std::vector<std::uint8_t>& b) {
  using walk::model::FileHeader;
  using walk::model::SectionEntry;
  if (b.size() < sizeof(FileHeader)) return;
  FileHeader h;
  std::memcpy(&h, b.data(), sizeof h);
  h.magic = walk::model::kBundleMagic;
  h.version = walk::model::kBundleVersion;
  h.file_size = b.size();
  const std::size_t sections =
      std::min<std::size_t>(h.section_count, (b.size() - sizeof h) / sizeof(SectionEntry));
  for (std::size_t i = 0; i < sections; ++i) {
    SectionEntry e;
    std::uint8_t* at = b.data() + sizeof h + i * sizeof e;
    std::memcpy(&e, at, sizeof e);
    if (e.offset <= b.size() && e.record_size > 0 && e.count <= (b.size() - e.offset) / e.record_size)
      e.crc = crc(b.data() + e.offset, e.count * e.record_size);
    std::memcpy(at, &e, sizeof e);
  }
  if (sizeof h + std::size_t(h.section_count) * sizeof(SectionEntry) <= b.size())
    h.table_crc = crc(b.data() + sizeof h, std::size_t(h.section_count) * sizeof(SectionEntry));
  std::memcpy(b.data(), &h, sizeof h);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "input-" + std::to_string(::getpid()) + ".walk";
  std::vector<std::uint8_t> bytes(data, data + size);
  repair_checksums(bytes);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  try {
    const auto bundle = walk::model::Bundle::open(path);
    // A bundle that opens is walked as the renderer walks it: every view in range.
    for (std::uint32_t c = 0; c < bundle->cells().size(); ++c) (void)bundle->cell_polygons(c);
    const double origin[3] = {0.0, 0.0, 0.0};
    (void)bundle->locate_cell(origin);
  } catch (const walk::Error& e) {
    walk::fuzz::check_located(e, path);
  }
  return 0;
}
