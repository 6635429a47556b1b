#include "compiler/lighting/probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "common/parallel_for.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/lighting/stored_light.hpp"
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

model::Vec3 unit(const model::Vec3& v, const char* what) {
  const double len = std::sqrt(glm::dot(v, v));
  if (!(len > 1e-12) || !std::isfinite(len))
    throw Error(std::string("walk probe: ") + what + " must be a finite, non-zero direction");
  return v / len;
}

}  // namespace

struct Probe::Impl {
  const model::Bundle& bundle;
  StoredLight stored;
  std::vector<model::Luminaire> luminaires;
};

Probe::Probe(const model::Bundle& b)
    : impl_(std::make_unique<Impl>(Impl{b, StoredLight(b), model::load_luminaires(b)})) {}

Probe::~Probe() = default;

ProbeResult Probe::read(const ProbeOptions& o) const {
  const model::Bundle& b = impl_->bundle;
  const StoredLight& stored = impl_->stored;
  const TriangleBvh& bvh = stored.bvh();
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
  for (const CircuitLight& e : direct.row(0))
    r.circuits[e.circuit].direct_lux = model::lux_from_irradiance({e.rgb[0], e.rgb[1], e.rgb[2]});

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
      if (!stored.along_ray(start, cosine_direction(n, u1, u2), radiosity, back)) {
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
    if (stored.along_ray(at, unit(*o.look, "--look"), radiosity, back, &distance)) {
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
