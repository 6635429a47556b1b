#include "common/hash.hpp"

#include <xxhash.h>

#include <fstream>
#include <vector>

namespace walk {

std::uint64_t hash_bytes(std::uint64_t seed, const void* data, std::size_t size) {
  return XXH3_64bits_withSeed(data, size, seed);
}

std::uint64_t hash_file(std::uint64_t seed, const std::string& path) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset_withSeed(state, seed);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    XXH3_64bits_update(state, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  const std::uint64_t h = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return h;
}

}  // namespace walk
