#include "compiler/raycast/bvh_caster.hpp"

#include <glm/geometric.hpp>

namespace walk::compiler {
namespace {

std::vector<Triangle> indexed_local(std::span<const Triangle> input, const model::Vec3& centre) {
  std::vector<Triangle> out;
  out.reserve(input.size());
  for (std::uint32_t i = 0; i < input.size(); ++i)
    out.push_back({input[i].a - centre, input[i].b - centre, input[i].c - centre, i});
  return out;
}

}  // namespace

BvhCaster::BvhCaster(std::span<const Triangle> triangles)
    : centre_(whole_metre_centre(triangles)), bvh_(indexed_local(triangles, centre_)) {
  polygon_.reserve(triangles.size());
  normals_.reserve(triangles.size());
  for (const auto& t : triangles) {
    polygon_.push_back(t.polygon);
    normals_.push_back(glm::cross(t.b - t.a, t.c - t.a));
  }
}

RayHit BvhCaster::closest(const Ray& ray) const {
  if (!valid_ray(ray)) return {};
  const auto h = bvh_.closest(ray.origin - centre_, ray.dir, ray.tmin, ray.tmax);
  if (!h) return {};
  const std::uint32_t i = bvh_.triangles()[h->triangle].polygon;
  return {h->t, i, polygon_[i], glm::dot(normals_[i], ray.dir) < 0.0};
}

bool BvhCaster::occluded(const Ray& ray) const {
  if (!valid_ray(ray)) return false;
  return bvh_.occluded(ray.origin - centre_, ray.dir, ray.tmin, ray.tmax);
}

std::size_t BvhCaster::memory_bytes() const {
  // TriangleBvh does not report its node count; a median split with leaves of up to 4 has at most
  // 2n/4 + 1 nodes of 56 bytes (two Vec3 and two uint32).
  const std::size_t n = bvh_.triangles().size();
  return n * sizeof(Triangle) + (n / 2 + 1) * 56 + polygon_.capacity() * 4 + normals_.capacity() * 24;
}

}  // namespace walk::compiler
