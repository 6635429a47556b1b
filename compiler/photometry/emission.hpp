#pragma once
// A photometric luminaire's emission in world directions: the intensity its table gives towards a
// direction (for gathering direct light) and directions drawn in proportion to it (for shooting), so that
// both ways of lighting agree.
#include <vector>

#include "model/model.hpp"

namespace walk::compiler {

// The luminaire's C-gamma frame: gamma 0 along `aim`, C0 towards `c0`, C90 towards c0 x aim
// (counter-clockwise seen from behind the luminaire, as LM-63 defines C).
struct PhotometricFrame {
  model::Vec3 aim{0.0, 0.0, -1.0};
  model::Vec3 c0{1.0, 0.0, 0.0};
  model::Vec3 c90{0.0, 1.0, 0.0};
  explicit PhotometricFrame(const model::Luminaire& l);
  PhotometricFrame() = default;
  // Gamma and C, degrees, of unit direction w.
  void angles(const model::Vec3& w, double& gamma, double& c) const;
  [[nodiscard]] model::Vec3 direction(double gamma_rad, double c_rad) const;
};

// Radiant intensity per watt of the luminaire's power towards unit direction `w` (W/sr per W): its table's
// candela over its table's flux.
[[nodiscard]] double photometric_intensity_per_watt(const model::Luminaire& l, const model::Vec3& w);

// Directions distributed as a table's intensity: the sphere cut into cells (1 degree of gamma by 5 of C),
// each chosen with probability intensity x solid angle, then a uniform point of the cell in (cos gamma, C).
class EmissionSampler {
 public:
  EmissionSampler(const model::IntensityDistribution& d, const PhotometricFrame& frame);
  // (u1, u2) uniform in [0, 1)^2.
  [[nodiscard]] model::Vec3 sample(double u1, double u2) const;

 private:
  PhotometricFrame frame_;
  int c_cells_ = 1;
  std::vector<double> cdf_;  // per cell, cumulative, last = 1
};

}  // namespace walk::compiler
