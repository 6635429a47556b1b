#pragma once
// One hash for every "inputs unchanged" check (scene, light stage, compiler identity): XXH3-64 from
// Debian's libxxhash, chained by seed so that a sequence of parts hashes like one stream of them.
#include <cstdint>
#include <string>

namespace walk {

// The hash of `size` bytes at `data`, seeded by the hash of what came before (any value to start).
[[nodiscard]] std::uint64_t hash_bytes(std::uint64_t seed, const void* data, std::size_t size);
// The hash of a file's contents after `seed`; a file that cannot be read hashes as empty.
[[nodiscard]] std::uint64_t hash_file(std::uint64_t seed, const std::string& path);

}  // namespace walk
