#pragma once
// `walk probe`: illuminance at a point of a compiled bundle, per circuit, the way a light meter would read
// it. Direct light is gathered from the bundle's luminaires (panels sampled over their area, points and
// fixtures from their intensity), indirect light by cosine-distributed rays that read the radiosity the
// light stage stored on the surfaces they hit. Both in the units the solver used (docs/RADIOSITY.md).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::compiler {

struct ProbeOptions {
  model::Vec3 at{0.0};                // world metres (the scene's coordinates, z up)
  model::Vec3 normal{0.0, 0.0, 1.0};  // of the meter's face; any length but zero
  std::optional<model::Vec3> look;    // a direction: also report the luminance of what it meets
  int indirect_rays = 16384;          // cosine-distributed rays for the indirect part
  int panel_samples = 256;            // stratified points per area luminaire
  unsigned threads = 2;
};

struct CircuitReading {
  std::string name;
  double direct_lux = 0.0;
  double indirect_lux = 0.0;
  double indirect_standard_error = 0.0;  // lux, of the indirect estimate
  double look_luminance = 0.0;           // cd/m2 of the surface `look` meets (reflected light only)
};

struct ProbeResult {
  std::vector<CircuitReading> circuits;  // at full level, in the bundle's circuit order
  double back_face_fraction = 0.0;       // of the indirect rays: high when the point lies inside a wall
  std::optional<double> look_distance;   // metres to the surface `look` meets, when it meets one
};

// A light meter for one bundle: its surfaces' BVH and its luminaires are built once, so a survey of many
// points pays for them once. The bundle must outlive the probe.
class Probe {
 public:
  explicit Probe(const model::Bundle& bundle);
  ~Probe();
  // Throws walk::Error for a zero normal or look direction or a point that is not finite.
  [[nodiscard]] ProbeResult read(const ProbeOptions& options) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace walk::compiler
