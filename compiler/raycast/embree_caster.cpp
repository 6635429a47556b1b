#include "compiler/raycast/embree_caster.hpp"

#include <string>

#include "model/error.hpp"

#ifdef WALK_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "compiler/raycast/local_triangles.hpp"

namespace walk::compiler {
namespace {

// Embree's memory monitor: bytes it has allocated for this device (scene, BVH, buffers).
bool monitor(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<std::int64_t>*>(user)->fetch_add(bytes);
  return true;
}

float clamp_float(double x) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return static_cast<float>(x > kMax ? kMax : x);
}

// What the exact variant's filter needs of a ray, behind Embree's context (which Embree hands to filters).
struct ExactContext {
  RTCIntersectContext base;  // first: Embree is given &base
  const std::vector<model::Vec3>* normals;
  const std::vector<double>* offsets;
  model::Vec3 origin, dir;  // local, in double
  double tmin, tmax;
};

// The ray parameter of triangle i's plane in double, from the ray's own double origin and direction:
// NaN or infinite for a ray in or parallel to the plane (which by the convention does not hit it).
double plane_t(const ExactContext& c, unsigned i) {
  const model::Vec3& n = (*c.normals)[i];
  return ((*c.offsets)[i] - glm::dot(n, c.origin)) / glm::dot(n, c.dir);
}

// Embree's hits confirmed in double: a hit counts only where the ray meets the triangle's plane within
// (tmin, tmax) in double. Embree's float origin lies up to a few micrometres off the surface a ray leaves
// (a float coordinate 50 m from the centre is good to 4 um, above the 1 um self-hit distance), so without
// this it reports that surface. Edges are left to Embree's own watertight float test: rejecting by a
// double edge test could drop a hit whose neighbour Embree never reports.
void exact_filter(const RTCFilterFunctionNArguments* args) {
  const auto& c = *reinterpret_cast<const ExactContext*>(args->context);
  for (unsigned j = 0; j < args->N; ++j) {
    if (args->valid[j] != -1) continue;
    const double t = plane_t(c, RTCHitN_primID(args->hit, args->N, j));
    if (!(t > c.tmin && t < c.tmax)) args->valid[j] = 0;
  }
}

class EmbreeCaster final : public RayCaster {
 public:
  EmbreeCaster(std::span<const Triangle> triangles, bool exact) : local_(triangles), exact_(exact) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("embree: rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(device_, monitor, &bytes_);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t n = local_.triangles.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * n));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = local_.triangles[i];
      const model::Vec3* p[3] = {&t.a, &t.b, &t.c};
      for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) v[9 * i + 3 * c + a] = static_cast<float>((*p[c])[a]);
        idx[3 * i + c] = static_cast<unsigned>(3 * i + c);
      }
    }
    if (exact_) {
      if (!rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
        throw Error("ray caster 'embree-exact': this Embree was built without filter functions");
      rtcSetGeometryIntersectFilterFunction(geom, exact_filter);
      rtcSetGeometryOccludedFilterFunction(geom, exact_filter);
      offsets_.reserve(n);
      for (std::size_t i = 0; i < n; ++i)
        offsets_.push_back(glm::dot(local_.normals[i], local_.triangles[i].a));
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
    // Keep only what hits report: polygon ids and normals (28 bytes a triangle, not the vertices).
    polygon_.reserve(n);
    for (const auto& t : local_.triangles) polygon_.push_back(t.polygon);
    std::vector<Triangle>().swap(local_.triangles);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw Error("embree: scene build failed");
  }
  ~EmbreeCaster() override {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeCaster(const EmbreeCaster&) = delete;
  EmbreeCaster& operator=(const EmbreeCaster&) = delete;

  [[nodiscard]] std::string_view name() const override { return exact_ ? "embree-exact" : "embree"; }

  [[nodiscard]] RayHit closest(const Ray& ray) const override {
    if (!valid_ray(ray)) return {};
    RTCRayHit rh{};
    fill(ray, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    double t = INFINITY;
    if (exact_) {  // the plain reference keeps Embree's own context: nothing added to its rays
      ExactContext ctx = context(ray);
      rtcIntersect1(scene_, &ctx.base, &rh);
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) t = plane_t(ctx, rh.hit.primID);
    } else {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      rtcIntersect1(scene_, &ctx, &rh);
      t = rh.ray.tfar;
    }
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    const std::uint32_t i = rh.hit.primID;
    return {t, i, polygon_[i], local_.front(i, ray.dir)};
  }

  [[nodiscard]] bool occluded(const Ray& ray) const override {
    if (!valid_ray(ray)) return false;
    RTCRay r{};
    fill(ray, r);
    if (exact_) {
      ExactContext ctx = context(ray);
      rtcOccluded1(scene_, &ctx.base, &r);
    } else {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      rtcOccluded1(scene_, &ctx, &r);
    }
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }

  [[nodiscard]] std::size_t memory_bytes() const override {
    return static_cast<std::size_t>(bytes_.load()) + local_.memory_bytes() + polygon_.capacity() * 4 +
           offsets_.capacity() * sizeof(double);
  }

 private:
  void fill(const Ray& ray, RTCRay& r) const {
    const model::Vec3 o = ray.origin - local_.centre;
    r.org_x = static_cast<float>(o.x);
    r.org_y = static_cast<float>(o.y);
    r.org_z = static_cast<float>(o.z);
    r.dir_x = static_cast<float>(ray.dir.x);
    r.dir_y = static_cast<float>(ray.dir.y);
    r.dir_z = static_cast<float>(ray.dir.z);
    r.tnear = static_cast<float>(std::max(ray.tmin, 0.0));
    r.tfar = clamp_float(ray.tmax);
    r.mask = 0xFFFFFFFFu;
    r.flags = 0;
  }

  [[nodiscard]] ExactContext context(const Ray& ray) const {
    ExactContext c{};
    rtcInitIntersectContext(&c.base);
    c.normals = &local_.normals;
    c.offsets = &offsets_;
    c.origin = ray.origin - local_.centre;
    c.dir = ray.dir;
    c.tmin = std::max(ray.tmin, 0.0);
    c.tmax = ray.tmax;
    return c;
  }

  LocalTriangles local_;  // centre and normals (facing); its triangles are dropped after the build
  bool exact_;
  std::vector<double> offsets_;  // exact variant: each triangle's plane, dot(normal, p) == offset
  std::vector<std::uint32_t> polygon_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::atomic<std::int64_t> bytes_{0};
};

}  // namespace

bool embree_available() {
  return true;
}

std::unique_ptr<RayCaster> make_embree_caster(std::span<const Triangle> triangles, bool exact) {
  return std::make_unique<EmbreeCaster>(triangles, exact);
}

}  // namespace walk::compiler

#else

namespace walk::compiler {

bool embree_available() {
  return false;
}

std::unique_ptr<RayCaster> make_embree_caster(std::span<const Triangle>, bool exact) {
  throw Error(std::string("ray caster '") + (exact ? "embree-exact" : "embree") +
              "': this build has no Embree (WALK_WITH_EMBREE=OFF or libembree-dev missing)");
}

}  // namespace walk::compiler

#endif
