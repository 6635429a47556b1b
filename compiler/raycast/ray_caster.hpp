#pragma once
// One ray-casting interface for every stage that shoots rays (direct light, radiosity, visibility sampling),
// with several interchangeable structures behind it, chosen by name:
//   "axial"  the paper's structure: axial polygons by plane, three sorted plane lists walked in merged order
//            of ray parameter with a 2D grid inside each plane, plus a BSP tree for the non-axial rest;
//   "bvh"    the skeleton's median-split TriangleBvh;
//   "brute"  every triangle, every ray: the reference the others are tested against;
//   "embree" Intel Embree 3 (single precision), only when built with WALK_WITH_EMBREE: the speed reference.
//            Its float origin lies micrometres off the surface a ray leaves, so it breaks the self-hit
//            policy;
//   "embree-exact" the same, each hit confirmed in double (the plane's t within (tmin, tmax)): it keeps the
//            policy, and is the Embree to choose for lighting and visibility.
//
// Conventions shared by every backend:
// - Input is triangles carrying the id of the polygon they came from; hits name both.
// - Hits count only for tmin < t < tmax (t in units of dir, which need not be unit length); tmin < 0 counts
// as 0.
// - Self-hit policy: a ray leaving a surface must start at tmin = self_hit_tmin(dir); then it never reports
//   the surface it starts on, nor any other within kSelfHitDistance. With tmin = 0 it may or may not.
// - A ray lying in a polygon's plane does not hit that polygon (zero-area intersection); it hits what it
//   meets across its path.
// - Closest hit: smallest t; hits within kTieDistance of each other are a tie, won by the polygon whose front
//   (counter-clockwise) side faces the ray, then by the lowest triangle index (back-to-back walls of adjacent
//   zones are then resolved towards the room the ray is in). Embree breaks ties its own way.
// - Every backend works relative to a whole-metre centre of the model, so a model far from the origin gives
//   the same answers as near it.
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/raycast/triangle_bvh.hpp"
#include "model/model.hpp"

namespace walk::compiler {

// Distance along a ray within which a surface counts as the one the ray leaves (1 micrometre: far above the
// 1e-13 m rounding of double coordinates in a 1 km building, far below any gap a building has).
inline constexpr double kSelfHitDistance = 1e-6;
// Hits closer together than this along the ray are a tie (1 nm: coplanar duplicates, shared edges).
inline constexpr double kTieDistance = 1e-9;
inline constexpr std::uint32_t kNoHit = std::numeric_limits<std::uint32_t>::max();

struct Ray {
  model::Vec3 origin{0.0};
  model::Vec3 dir{0.0, 0.0, 1.0};
  double tmin = 0.0;
  double tmax = std::numeric_limits<double>::infinity();
};

struct RayHit {
  double t = std::numeric_limits<double>::infinity();
  std::uint32_t triangle = kNoHit;
  std::uint32_t polygon = kNoHit;
  bool front = false;  // the ray meets the triangle's counter-clockwise side
  [[nodiscard]] bool hit() const { return triangle != kNoHit; }
};

// tmin for a ray of direction `dir` leaving a surface (see the self-hit policy above).
[[nodiscard]] inline double self_hit_tmin(const model::Vec3& dir) {
  const double len = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
  return len > 0.0 ? kSelfHitDistance / len : 0.0;
}

// Finite origin and direction, direction not zero: other rays hit nothing in every backend.
[[nodiscard]] inline bool valid_ray(const Ray& r) {
  const auto& o = r.origin;
  const auto& d = r.dir;
  return std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) &&
         std::isfinite(d.y) && std::isfinite(d.z) && (d.x != 0.0 || d.y != 0.0 || d.z != 0.0) &&
         !std::isnan(r.tmin) && !std::isnan(r.tmax);
}

// kTieDistance in units of a ray's t.
[[nodiscard]] inline double tie_tolerance(const model::Vec3& dir) {
  const double len = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
  return len > 0.0 ? kTieDistance / len : 0.0;
}

class RayCaster {
 public:
  virtual ~RayCaster() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual RayHit closest(const Ray& ray) const = 0;
  [[nodiscard]] virtual bool occluded(const Ray& ray) const = 0;
  // Bytes held by the structure (triangles, nodes, indices), for the benchmark's memory column.
  [[nodiscard]] virtual std::size_t memory_bytes() const = 0;

  // Batches on `threads` std::threads (1 runs on the caller's thread); hits.size() must equal rays.size().
  void closest_batch(std::span<const Ray> rays, std::span<RayHit> hits, unsigned threads) const;
  void occluded_batch(std::span<const Ray> rays, std::span<std::uint8_t> occluded, unsigned threads) const;
};

// Names accepted by make_ray_caster in this build ("embree" and "embree-exact" only when compiled in).
[[nodiscard]] std::vector<std::string> ray_caster_names();
// Builds the named structure over `triangles` (copied); throws walk::Error for an unknown name.
[[nodiscard]] std::unique_ptr<RayCaster> make_ray_caster(std::string_view name,
                                                         std::span<const Triangle> triangles);

// Whole-metre point near the centre of the triangles' bounds: backends subtract it from vertices and ray
// origins (exactly, for a model far from the origin) so precision does not depend on where the model sits.
[[nodiscard]] model::Vec3 whole_metre_centre(std::span<const Triangle> triangles);

// Runs body(first, last) over [0, count) in chunks on `threads` threads (the batch helpers use it).
void parallel_chunks(std::size_t count, unsigned threads,
                     const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace walk::compiler
