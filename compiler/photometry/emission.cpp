#include "compiler/photometry/emission.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace walk::compiler {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr int kGammaCells = 180;  // 1 degree: finer than any published table's vertical spacing
constexpr int kCCells = 72;       // 5 degrees: the usual horizontal spacing

}  // namespace

PhotometricFrame::PhotometricFrame(const model::Luminaire& l) {
  aim = glm::normalize(l.normal);
  c0 = l.u_axis - glm::dot(l.u_axis, aim) * aim;
  c0 = glm::dot(c0, c0) > 1e-12 ? glm::normalize(c0) : glm::normalize(glm::cross(aim, model::Vec3(0, 0, 1)));
  c90 = glm::cross(c0, aim);
}

void PhotometricFrame::angles(const model::Vec3& w, double& gamma, double& c) const {
  gamma = std::acos(std::clamp(glm::dot(w, aim), -1.0, 1.0)) / kDegree;
  c = std::atan2(glm::dot(w, c90), glm::dot(w, c0)) / kDegree;
  if (c < 0.0) c += 360.0;
}

model::Vec3 PhotometricFrame::direction(double gamma_rad, double c_rad) const {
  const double s = std::sin(gamma_rad);
  return aim * std::cos(gamma_rad) + (c0 * std::cos(c_rad) + c90 * std::sin(c_rad)) * s;
}

double photometric_intensity_per_watt(const model::Luminaire& l, const model::Vec3& w) {
  if (!l.distribution) return 0.0;
  double gamma = 0.0, c = 0.0;
  PhotometricFrame(l).angles(w, gamma, c);
  return l.distribution->lumens > 0.0 ? l.distribution->candela_at(gamma, c) / l.distribution->lumens : 0.0;
}

EmissionSampler::EmissionSampler(const model::IntensityDistribution& d, const PhotometricFrame& frame)
    : frame_(frame), c_cells_(d.c_deg.size() == 1 ? 1 : kCCells) {
  cdf_.reserve(std::size_t(kGammaCells) * c_cells_);
  double total = 0.0;
  for (int i = 0; i < kGammaCells; ++i) {
    const double solid = (std::cos(i * kDegree) - std::cos((i + 1) * kDegree)) / c_cells_;
    for (int j = 0; j < c_cells_; ++j) {
      total += d.candela_at(i + 0.5, (j + 0.5) * 360.0 / c_cells_) * solid;
      cdf_.push_back(total);
    }
  }
  for (auto& v : cdf_) v /= total;
  cdf_.back() = 1.0;
}

model::Vec3 EmissionSampler::sample(double u1, double u2) const {
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u1);
  const std::size_t k = std::min<std::size_t>(it - cdf_.begin(), cdf_.size() - 1);
  const double below = k == 0 ? 0.0 : cdf_[k - 1];
  const double t = cdf_[k] > below ? std::clamp((u1 - below) / (cdf_[k] - below), 0.0, 1.0) : 0.5;
  const int i = static_cast<int>(k) / c_cells_, j = static_cast<int>(k) % c_cells_;
  // Uniform in solid angle within the cell: cos gamma uniform between the cell's edges.
  const double cos_gamma = std::cos(i * kDegree) + t * (std::cos((i + 1) * kDegree) - std::cos(i * kDegree));
  const double c = (j + u2) * 2.0 * std::numbers::pi / c_cells_;
  return frame_.direction(std::acos(std::clamp(cos_gamma, -1.0, 1.0)), c);
}

}  // namespace walk::compiler
