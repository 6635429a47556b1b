#include "compiler/lighting/probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "common/parallel_for.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/lighting/drawn_triangles.hpp"
#include "compiler/radiosity/sampling.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/error.hpp"
#include "model/luminaire_shapes.hpp"
#include "model/photometric_units.hpp"

namespace walk::compiler {
namespace {

// Indirect rays start this far off the meter's face (metres), as the direct light's shadow rays do: far
// above round-off at building scale, below any real gap.
constexpr double kRayOffset = 1e-4;
// Coincident back-to-back walls: hits within this (metres) go to the face looking back at the ray.
constexpr double kTieDistance = 1e-6;

model::Vec3 unit(const model::Vec3& v, const char* what) {
  const double len = std::sqrt(glm::dot(v, v));
  if (!(len > 1e-12) || !std::isfinite(len))
    throw Error(std::string("walk probe: ") + what + " must be a finite, non-zero direction");
  return v / len;
}

// Radiosity per circuit and channel where a ray from `origin` along `dir` first meets a surface's front,
// interpolated from its corners; false for a miss or a back face (the inside of a wall).
bool radiosity_at_hit(const model::Bundle& b, const std::vector<TriangleCorners>& corners,
                      const TriangleBvh& bvh, const model::Vec3& origin, const model::Vec3& dir,
                      std::vector<double>& out, bool& back, double* distance = nullptr) {
  back = false;
  const auto hit = bvh.closest_facing(origin, dir, 0.0, 1e30, kTieDistance);
  if (!hit) return false;
  const Triangle& t = bvh.triangles()[hit->triangle];
  const auto& c = corners[t.polygon];
  if (glm::dot(dir, vertex_normal(b.vertices()[c[0]])) >= 0.0) {
    back = true;
    return false;
  }
  if (distance) *distance = hit->t * std::sqrt(glm::dot(dir, dir));
  // Barycentric weights of the hit point in the triangle.
  const model::Vec3 p = origin + dir * hit->t;
  const model::Vec3 e1 = t.b - t.a, e2 = t.c - t.a, d = p - t.a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  double w1 = det > 0.0 ? (d22 * d1 - d12 * d2) / det : 1.0 / 3.0;
  double w2 = det > 0.0 ? (d11 * d2 - d12 * d1) / det : 1.0 / 3.0;
  w1 = std::clamp(w1, 0.0, 1.0);
  w2 = std::clamp(w2, 0.0, 1.0 - w1);
  const double w[3] = {1.0 - w1 - w2, w1, w2};
  const std::size_t k = b.circuits().size() * 3;
  out.assign(k, 0.0);
  for (int i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < k; ++j) out[j] += w[i] * b.light()[c[i] * k + j];
  return true;
}

}  // namespace

struct Probe::Impl {
  const model::Bundle& bundle;
  std::vector<TriangleCorners> corners;  // per BVH triangle id
  std::unique_ptr<TriangleBvh> bvh;
  std::vector<model::Luminaire> luminaires;
};

Probe::Probe(const model::Bundle& b) : impl_(std::make_unique<Impl>(Impl{b, drawn_triangles(b), {}, {}})) {
  std::vector<Triangle> triangles;
  const auto v = b.vertices();
  for (std::size_t i = 0; i < impl_->corners.size(); ++i) {
    const auto& c = impl_->corners[i];
    triangles.push_back({vertex_position(v[c[0]]), vertex_position(v[c[1]]), vertex_position(v[c[2]]),
                         static_cast<std::uint32_t>(i)});
  }
  impl_->bvh = std::make_unique<TriangleBvh>(std::move(triangles));
  impl_->luminaires = model::load_luminaires(b);
}

Probe::~Probe() = default;

ProbeResult Probe::read(const ProbeOptions& o) const {
  const model::Bundle& b = impl_->bundle;
  const TriangleBvh& bvh = *impl_->bvh;
  const auto& m = b.meta();
  const model::Vec3 origin_world(m.origin[0], m.origin[1], m.origin[2]);
  if (!std::isfinite(glm::dot(o.at, o.at))) throw Error("walk probe: --at must be a finite point");
  const model::Vec3 at = o.at - origin_world;
  const model::Vec3 n = unit(o.normal, "--normal");
  const std::size_t circuits = b.circuits().size();
  ProbeResult r;
  for (const auto& c : b.circuits()) r.circuits.push_back({std::string(b.string(c.name))});

  // Direct: a white meter's radiosity is its irradiance.
  const SurfaceSample meter{at, n, model::Rgb(1.0)};
  const auto direct =
      direct_light({&meter, 1}, impl_->luminaires, circuits, bvh, {o.panel_samples, o.threads});
  for (std::size_t c = 0; c < circuits; ++c)
    r.circuits[c].direct_lux =
        model::lux_from_irradiance({direct[c * 3], direct[c * 3 + 1], direct[c * 3 + 2]});

  // Indirect: E = mean radiosity met by cosine-distributed rays (pdf cos / pi cancels the cosine and pi).
  const int rays = std::max(1, o.indirect_rays);
  const int side = static_cast<int>(std::sqrt(double(rays)));
  std::vector<double> lux(std::size_t(rays) * circuits, 0.0);
  std::vector<std::uint8_t> backs(rays, 0);
  const model::Vec3 start = at + n * kRayOffset;
  parallel_ranges(rays, 512, o.threads, [&](std::size_t first, std::size_t last) {
    std::vector<double> radiosity;
    for (std::size_t i = first; i < last; ++i) {
      SplitMix rng(mix_seed(0x9e3779b9, i));
      double u1 = rng.uniform(), u2 = rng.uniform();
      if (int(i) < side * side) {
        u1 = ((i % side) + u1) / side;
        u2 = ((i / side) + u2) / side;
      }
      bool back = false;
      if (!radiosity_at_hit(b, impl_->corners, bvh, start, cosine_direction(n, u1, u2), radiosity, back)) {
        backs[i] = back;
        continue;
      }
      for (std::size_t c = 0; c < circuits; ++c)
        lux[i * circuits + c] =
            model::lux_from_irradiance({radiosity[c * 3], radiosity[c * 3 + 1], radiosity[c * 3 + 2]});
    }
  });
  for (std::size_t c = 0; c < circuits; ++c) {
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < rays; ++i) {
      const double x = lux[std::size_t(i) * circuits + c];
      sum += x;
      sum2 += x * x;
    }
    const double mean = sum / rays;
    r.circuits[c].indirect_lux = mean;
    // Plain-random standard error: strata make the true error smaller, so this bounds it.
    r.circuits[c].indirect_standard_error = std::sqrt(std::max(0.0, sum2 / rays - mean * mean) / rays);
  }
  r.back_face_fraction = double(std::count(backs.begin(), backs.end(), 1)) / rays;

  if (o.look) {
    std::vector<double> radiosity;
    bool back = false;
    double distance = 0.0;
    if (radiosity_at_hit(b, impl_->corners, bvh, at, unit(*o.look, "--look"), radiosity, back, &distance)) {
      r.look_distance = distance;
      // A diffuse surface of radiosity B has luminance B / pi.
      for (std::size_t c = 0; c < circuits; ++c)
        r.circuits[c].look_luminance =
            model::lux_from_irradiance({radiosity[c * 3], radiosity[c * 3 + 1], radiosity[c * 3 + 2]}) /
            std::numbers::pi;
    }
  }
  return r;
}

}  // namespace walk::compiler
