#include "compiler/raycast/ray_caster.hpp"

#include <algorithm>
#include <atomic>

#include "common/parallel_for.hpp"
#include "compiler/raycast/axial_caster.hpp"
#include "compiler/raycast/brute_force_caster.hpp"
#include "compiler/raycast/bvh_caster.hpp"
#include "compiler/raycast/embree_caster.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

// Rays per work item: large enough that the shared counter is touched rarely, small enough to balance.
constexpr std::size_t kChunk = 1024;

}  // namespace

void parallel_chunks(std::size_t count, unsigned threads,
                     const std::function<void(std::size_t, std::size_t)>& body) {
  parallel_ranges(count, kChunk, threads, body);
}

void RayCaster::closest_batch(std::span<const Ray> rays, std::span<RayHit> hits, unsigned threads) const {
  if (hits.size() != rays.size()) throw Error("closest_batch: hits and rays differ in size");
  parallel_chunks(rays.size(), threads, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) hits[i] = closest(rays[i]);
  });
}

void RayCaster::occluded_batch(std::span<const Ray> rays, std::span<std::uint8_t> occluded_out,
                               unsigned threads) const {
  if (occluded_out.size() != rays.size()) throw Error("occluded_batch: output and rays differ in size");
  parallel_chunks(rays.size(), threads, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) occluded_out[i] = occluded(rays[i]) ? 1 : 0;
  });
}

model::Vec3 whole_metre_centre(std::span<const Triangle> triangles) {
  model::Bounds b;
  for (const auto& t : triangles) {
    b.add(t.a);
    b.add(t.b);
    b.add(t.c);
  }
  if (b.empty()) return model::Vec3(0.0);
  const model::Vec3 c = b.centre();
  return {std::round(c.x), std::round(c.y), std::round(c.z)};
}

std::vector<std::string> ray_caster_names() {
  std::vector<std::string> names{"axial", "bvh", "brute"};
  if (embree_available()) {
    names.emplace_back("embree");
    names.emplace_back("embree-exact");
  }
  return names;
}

std::unique_ptr<RayCaster> make_ray_caster(std::string_view name, std::span<const Triangle> triangles) {
  if (name == "axial") return std::make_unique<AxialCaster>(triangles);
  if (name == "bvh") return std::make_unique<BvhCaster>(triangles);
  if (name == "brute") return std::make_unique<BruteForceCaster>(triangles);
  // Without Embree compiled in, make_embree_caster throws the error that says so.
  if (name == "embree" || name == "embree-exact")
    return make_embree_caster(triangles, name == "embree-exact");
  std::string known;
  for (const auto& n : ray_caster_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown ray caster '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace walk::compiler
