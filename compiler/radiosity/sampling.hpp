#pragma once
// Deterministic random numbers and the sample warps used for shooting: the same seed gives the same rays
// whatever the thread count, so compiles are reproducible.
#include <cstdint>

#include "model/model.hpp"

namespace walk::compiler {

// SplitMix64: tiny state, good enough for sampling, and seedable per ray.
class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

[[nodiscard]] std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b);

// Cosine-weighted direction about `normal` from (u1, u2) in [0,1)^2 (Malley's method).
[[nodiscard]] model::Vec3 cosine_direction(const model::Vec3& normal, double u1, double u2);
// Uniform point in a triangle from (u1, u2) in [0,1)^2.
[[nodiscard]] model::Vec3 triangle_point(const model::Vec3& a, const model::Vec3& b, const model::Vec3& c,
                                         double u1, double u2);
// Any unit vector perpendicular to n (n unit).
[[nodiscard]] model::Vec3 perpendicular(const model::Vec3& n);

}  // namespace walk::compiler
